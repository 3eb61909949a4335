"""python3 -m gransim.reproduce: the report of `gransim reproduce` (cli.py)"""
from .cli import main

main()
