"""Formatting of one metric for the Markdown tables of the benchmark scripts."""


def cell(value, scale=1.0, digits=1, unit="", missing="n/a"):
    """value * scale with `digits` decimals and `unit`; `missing` for None (a null metric)."""
    if value is None:
        return missing
    return f"{value * scale:.{digits}f}{unit}"
