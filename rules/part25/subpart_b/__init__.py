"""Part 25 Subpart B — Flight."""
