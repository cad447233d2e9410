"""``python -m certkit.cli``: the ``certkit`` program."""

from certkit.cli.main import entry

entry()
