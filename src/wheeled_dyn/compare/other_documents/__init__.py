r"""Documents that are not one derivation: published linearised equations, hand-made comparison tables."""
