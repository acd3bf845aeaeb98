"""The schedule: the rules run on the solver's shared state after every step."""
