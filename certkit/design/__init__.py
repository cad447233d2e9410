"""One design end to end: design variables, horizontal-tail sizing loop, mission, the design record."""
