r"""Other readings of a document — row factors and functions, combinations of the equations, sign conventions: how a difference is explained, never whether there is one."""
