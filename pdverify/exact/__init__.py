"""Exact solutions (closed form, no discretisation): the ground truth of the framework."""
