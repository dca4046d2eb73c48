r"""Both sides' numbers on a grid: the truth in the document's coordinates and the document's compiled elements, element by element."""
