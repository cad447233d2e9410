"""14 CFR Part 25 — Airworthiness standards: transport category airplanes."""
