"""Plots of gyroshell results: each function takes the result and ``ax=``, returns the Axes.

* :func:`mode_shape` - real or imaginary part of a complex (travelling) mode;
  :func:`mode_shape_parts` draws both side by side;
* :func:`field` - a deflection field (static solution, snapshot, any array on the grid);
* :func:`campbell` - frequencies against speed with tracked branches, crossings, veerings,
  excitation lines ω = n·2πV/ℓ and the critical speed;
* :func:`sweep` - frequencies against speed with the branches a sweep tracked;
* :func:`stability_map` - stable / divergence / flutter over two varied parameters;
* :func:`study_map` - a computed quantity over two varied parameters (a colour map);
* :func:`study_lines` - a computed quantity against one varied parameter;
* :func:`load_point_history`, :func:`head_histories`, :func:`wireframe`,
  :func:`waterfall`, :func:`period_vs_velocity`, :func:`spectra`, :func:`bode` - the
  drawings of ``gyroshell reproduce`` (load-point and moving-head histories, 3-D wire
  frames, centre-line waterfalls, period against speed, stacked spectra, frequency
  response), from arrays or results, so a notebook redraws them from its own runs;
* :func:`animate_mode`, :func:`animate_transient` - GIF animations (matplotlib + Pillow).

matplotlib is imported when a function is called, never at ``import gyroshell``. Without
``ax`` a new figure is made; :func:`save_figure` writes it atomically. :func:`pyplot` is
the one way gyroshell imports matplotlib.pyplot.
"""

from .animations import animate_mode, animate_transient
from .fields import field, mode_shape, mode_shape_parts
from .figures import pyplot, save_figure
from .reproductions import (
    bode,
    edge_reflection,
    head_histories,
    load_point_history,
    period_vs_velocity,
    spectra,
    waterfall,
    wave_fronts,
    wireframe,
)
from .spectrum import critical_speeds, eigenvalues
from .speed import campbell, sweep
from .study_maps import STABILITY_COLOURS, stability_map, study_lines, study_map

__all__ = ["STABILITY_COLOURS", "animate_mode", "animate_transient", "bode", "campbell",
           "critical_speeds", "edge_reflection", "eigenvalues", "field", "head_histories",
           "load_point_history", "mode_shape", "mode_shape_parts", "period_vs_velocity", "pyplot",
           "save_figure", "spectra", "stability_map", "study_lines", "study_map", "sweep",
           "waterfall", "wave_fronts", "wireframe"]
