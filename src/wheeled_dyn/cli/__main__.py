r"""``python -m wheeled_dyn.cli``: the ``wheeled-dyn`` command (:func:`.main.entry`)."""

from .main import entry

if __name__ == "__main__":
    entry()
