"""Loaded TCA from condensed flank compliances (issue 18): :mod:`.compliance`, :mod:`.contact`, :mod:`.run`."""
