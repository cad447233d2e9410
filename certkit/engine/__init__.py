"""The engine: the rule registry, the §25.21(a) condition spaces and loadings, the memoised Context of shared models,
the scheduler that runs rules over conditions, the results and their JSON form, the rule index and the rule scaffold.

Layer: above the models (:mod:`certkit.models`), below the rules (``certkit_rules``), the design layer, the study, the
report and the CLI. Evidence as data (:mod:`certkit.engine.evidence`) lives here because rules build it and the report
draws it.
"""
