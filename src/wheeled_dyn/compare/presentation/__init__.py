r"""Text attached to records for the reports (closed forms, printed expressions); never read by judge/ or causes/."""
