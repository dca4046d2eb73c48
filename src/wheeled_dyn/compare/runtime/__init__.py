r"""How comparisons run (worker processes, the results cache), not what they decide."""
