"""The report of `gransim reproduce`: each claim of a paper tested against the runs' data with
a stated rule, and a verdict (agrees, disagrees, not resolved). Run it as the command does:
python3 -m gransim.reproduce --study tapping|rfm --budget B DIR (cli.py).

  verdicts     the statistical tests and the rules that turn their p-values into verdicts
  tapping*     the tapping paper's claims; rfm, rfm_ring, rfm_data: the RFM thesis' claims,
               rfm_conditions: the thesis' conditions for each, checked against plan.json
  report       report.md, report.html and claims.csv; departures, described: what they say
  series       the series a report ships, from which it is written again (--from-series)

verdicts works on any numbers (numpy arrays of a user's own series); the claims read the folder
`gransim reproduce` writes. Needs numpy and matplotlib, not the compiled module.
"""
