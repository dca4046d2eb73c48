r"""From element records to the few reasons behind them (reads typed diagnoses, never text)."""
