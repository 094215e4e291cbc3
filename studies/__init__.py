"""Thesis studies: one module per figure set; each writes figures, CSV and JSON to --out."""
