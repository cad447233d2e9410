"""Structural sizing models: idealised box sections of lifting surfaces, the horizontal-tail group built
around its sized box, and the elevator actuators. Pure physics: loads and allowables in,
gauges, masses and mass properties out; nothing here knows the regulations."""
