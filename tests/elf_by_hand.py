"""ASCE 7-16 formulas written out again, independently of vdw_frames.asce7, for the tests to check it against."""


def hand_cs(spectrum, period, r, ie, *, minimum=True):
    """ASCE 7-16 Eqs. 12.8-2 ... 12.8-6, written out again."""
    sds, sd1, s1, tl = spectrum  # g, g, g or None, s
    value, equation = sds * ie / r, "12.8-2"
    bound = sd1 * ie / (period * r) if period <= tl else sd1 * tl * ie / (period**2 * r)
    if bound < value:
        value, equation = bound, ("12.8-3" if period <= tl else "12.8-4")
    if minimum and max(0.044 * sds * ie, 0.01) > value:
        value, equation = max(0.044 * sds * ie, 0.01), "12.8-5"
    if s1 is not None and s1 >= 0.6 and 0.5 * s1 * ie / r > value:
        value, equation = 0.5 * s1 * ie / r, "12.8-6"
    return value, equation
