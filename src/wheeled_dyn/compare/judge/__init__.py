r"""One element, or one equation, against the truth: the verdict and typed diagnoses, from numbers (pure functions)."""
