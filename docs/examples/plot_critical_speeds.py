"""
Critical speeds
===============

A placeholder example, replaced by the gallery's own.
"""
import gyroshell

print(gyroshell.__version__)
