r"""``python -m wheeled_dyn``: the ``wheeled-dyn`` command (:func:`.cli.main.entry`)."""

from .cli.main import entry

if __name__ == "__main__":
    entry()
