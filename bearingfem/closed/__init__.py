"""Closed forms: the short (Frene/Ocvirk) and long (Pinkus-Sternlicht) bearings of the seed
paper, and exact quadratures of the same analytic pressures."""
