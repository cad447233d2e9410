"""Design studies: many design evaluations over a design of experiments, and their analysis."""
