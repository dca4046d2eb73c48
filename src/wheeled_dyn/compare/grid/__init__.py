r"""On which numbers: K random parameter sets of a model (and its special families) and N states each, drawn where the document's assumptions put them."""
