"""Reference pages of the documentation, generated from the code when the site is built.

``hooks.py`` is the mkdocs hook (``mkdocs.yml``: ``hooks``); :mod:`.config_keys` writes the
configuration keys from :mod:`autobalance.config.schema` and the model dataclasses,
:mod:`.cli_pages` the commands and their options from the typer app and the vocabulary from
:mod:`autobalance.cli.vocabulary`. Nothing here is committed as a page: the pages are made
anew by every build, so they cannot drift from the code.
"""
