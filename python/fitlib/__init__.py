"""fitlib for Python: the C++ library's public API (docs/python.md).

Everything in ``fitlib._fitlib`` is re-exported here; ``fit_card`` is the one convenience: the
library call ``fitcli fit`` makes (card/fit_card.hpp: model options from the data, fit or term
selection, card) with the same defaults, so that it gives the CLI's card.
"""
from ._fitlib import *  # noqa: F401,F403
from ._fitlib import (FitOptions, Table, TermOptions, fit_table_card, read_table, __version__)


def fit_card(data, model, terms=4, *, format="native", mode="", temperature_law="none",
             reference_C=23.0, polynomial_degree=3, bulk_modulus=False, options=None,
             term_options=None, name=None, command="", record_timing=False, out=None):
    """``fitcli fit`` without its master-curve and relaxation branches.

    data: a path, a list of paths or a Table. terms: a number or "auto" (series models only).
    options: FitOptions (backend, residual, weights, ...); with terms="auto" and the spectrum
    method, an objective left at its defaults becomes the CLI's (relative, storage weight 80).
    Returns (card, result, selection); selection is None unless terms="auto". out: card file.
    """
    _require_bool(bulk_modulus, "bulk_modulus")
    table = data if isinstance(data, Table) else read_table(data, format=format, mode=mode)
    model_options = {"temperature_law": temperature_law, "reference_C": reference_C}
    if temperature_law == "polynomial":
        model_options["polynomial_degree"] = polynomial_degree
    if bulk_modulus:
        model_options["bulk_modulus"] = True
    card, result, selection = fit_table_card(
        table, model, str(terms), model_options, options if options is not None else FitOptions(),
        term_options if term_options is not None else TermOptions(), name or model + "-fit", command,
        record_timing)
    if out:
        card.save(out)
    return card, result, selection


def _require_bool(value, name):
    """The extension's check of a bool argument (bindings.hpp, boolean): True or False, a NumPy bool
    too; None, 0, 1 or any other object is a TypeError naming the argument (`if value:` read None
    as False)."""
    numpy_bool = type(value).__module__ == "numpy" and type(value).__name__ in ("bool_", "bool")
    if value is not True and value is not False and not numpy_bool:
        raise TypeError(f"{name} must be a bool (True or False), got {value!r}")
