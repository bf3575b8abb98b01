"""fitlib for Python: the C++ library's public API (docs/python.md).

Everything in ``fitlib._fitlib`` is re-exported here; ``fit_card`` is the one convenience, the
steps of ``fitcli fit`` (read, choose the model's options from the data, fit or select terms,
make the card) with the same defaults, so that it gives the CLI's card.
"""
from ._fitlib import *  # noqa: F401,F403
from ._fitlib import (FitOptions, InputError, Table, TermOptions, card_from_fit, fit, make_model,
                      read_table, select_terms, SPECTRUM_RESIDUAL, SPECTRUM_STORAGE_WEIGHT, __version__)


def fit_card(data, model, terms=4, *, format="native", mode="", temperature_law="none",
             reference_C=23.0, polynomial_degree=3, bulk_modulus=False, options=None,
             term_options=None, name=None, command="", record_timing=False, out=None):
    """``fitcli fit`` without its master-curve and relaxation branches.

    data: a path, a list of paths or a Table. terms: a number or "auto" (series models only).
    options: FitOptions (backend, residual, weights, ...); with terms="auto" and the spectrum
    method, an objective left at its defaults becomes the CLI's (relative, storage weight 80).
    Returns (card, result, selection); selection is None unless terms="auto". out: card file.
    """
    table = data if isinstance(data, Table) else read_table(data, format=format, mode=mode)
    if len(table) == 0:
        raise InputError("no usable rows")
    model_options = {"temperature_law": temperature_law, "reference_C": reference_C,
                     "mode": table.mode[0]}  # the mode of the data, as the CLI does
    if temperature_law == "polynomial":
        model_options["polynomial_degree"] = polynomial_degree
    if bulk_modulus:
        model_options["bulk_modulus"] = True
    options = options if options is not None else FitOptions()
    has_terms = "terms" in make_model(model, model_options).options
    selection = None
    if has_terms and terms == "auto":
        term_options = term_options if term_options is not None else TermOptions()
        default = FitOptions()
        if term_options.method == "spectrum" and (options.residual, options.storage_weight,
                                                  options.loss_weight) == (
                default.residual, default.storage_weight, default.loss_weight):
            options.residual = SPECTRUM_RESIDUAL
            options.storage_weight = SPECTRUM_STORAGE_WEIGHT
        selection = select_terms(model, model_options, table, options, term_options)
        result = selection.result
        result.messages = result.messages + selection.messages
    else:
        if has_terms:
            model_options["terms"] = int(terms)
        result = fit(make_model(model, model_options), table, options)
    card = card_from_fit(result, options, table, name or model + "-fit", command, record_timing)
    if out:
        card.save(out)
    return card, result, selection
