"""The paper's figures, one module per figure, named after the file it writes: ``<stem>.py``
writes ``<stem>.png`` and ``<stem>.pdf`` (``specification.py`` writes one plot per contested
claim into the folder ``specification/``). ``style.py`` holds the drawing helpers they share."""
