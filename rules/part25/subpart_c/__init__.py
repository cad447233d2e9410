"""Part 25 Subpart C — Structure."""
