"""Design studies: many design evaluations over a design of experiments, and their analysis."""


def load_surrogates(path):
    """The surrogates written by ``certkit study export --surrogates FILE``: a
    :class:`certkit.study.analysis.surrogate_file.SurrogateSet` with ``predict(points)`` (designs as rows in SI or
    mappings {variable path: value}) and ``possible(points)`` (the possible-design classifier)."""
    from certkit.study.analysis.surrogate_file import load_surrogates as load  # scikit-learn only when used

    return load(path)
