"""The RRT planner for grid maps (point vehicle and spaceships) and its CLI."""
