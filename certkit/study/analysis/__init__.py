"""Analysis of a design study: surrogates with goodness of fit, Monte Carlo feasibility, Pareto fronts,
single-objective optima, prediction profiler, global sensitivity and the self-contained HTML study report."""
