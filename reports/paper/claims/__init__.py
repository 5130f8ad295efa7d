"""The paper's claims as data: the ``Claim`` record, the register (every claim's quote, reading,
regime, rule and tolerance, written before any verdict), the rules and the tolerances of the
paper's words, the families of analyses and their agreement, and one ``*_claims`` module per
group of claims that decides them."""
