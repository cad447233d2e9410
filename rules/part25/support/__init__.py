"""Regulation support shared by the Part 25 rules: reference and control speeds, the thrust trims and loads-manoeuvre
set-up the rules' conditions state, the criteria tables, the check builders and the simulated procedures' batches.
These modules register no rule; every regulation-derived number here cites its paragraph."""
