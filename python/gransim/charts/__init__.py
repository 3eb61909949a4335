"""Charts of gransim's analyses, drawn with matplotlib (Agg) from the CSV and JSON files the
analyses write; `gransim analyze` and `gransim study` run them, and each runs on its own
(python3 -m gransim.charts.NAME DIR --help):

  tapping      the tapping study's charts from an analysis folder (φ̄ and σ_φ, KDE, Q, β)
  taprun       per-run charts of a tapping study (rest, segregation, stress)
  rfm          the Random Force Model charts of a folder of analysis CSV files
  rfm_compare  the RFM comparison charts (against the bisection process, across N)
  study        error against cost, and the stability map, of `gransim study`

The functions take file or folder paths and write PNG files; they need numpy and matplotlib,
not the compiled module.
"""
