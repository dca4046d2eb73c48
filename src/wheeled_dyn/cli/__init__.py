r"""The ``wheeled-dyn`` command: argument parsing, calls of the Python API, exit codes.
:mod:`.main` is the entry point; each ``*_cmd`` module adds its sub-commands."""
