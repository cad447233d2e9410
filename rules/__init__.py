"""Built-in regulation content: one module per paragraph (installed as ``certkit_rules``)."""
