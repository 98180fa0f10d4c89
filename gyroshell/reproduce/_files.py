"""The files each study writes into the output folder, known before it runs, so that an
output folder that could not take them is refused before any work
(:func:`output_files`); the runner checks each study's written files against them
(:func:`check_written`)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from pathlib import Path

#: Study name -> the names of the files it writes, in the order it writes them.
FILES: dict[str, tuple[str, ...]] = {
    "critical": ("critical_speeds.csv", "critical_speeds.md"),
    "fig2": ("fig2_load_point.csv", "fig2_steady_state.csv", "fig2_load_point.png"),
    "fig3": ("fig3_snapshots.csv", "fig3_wireframes.png"),
    "fig4": ("fig4_snapshots.csv", "fig4_wireframes.png"),
    "fig5": ("fig5_centerline.csv", "fig5_waterfall.png"),
    "fig6": ("fig6_centerline.csv", "fig6_waterfall.png"),
    "period": ("period_vs_velocity.csv", "period_spectra.csv", "period_vs_velocity.png"),
    "observations": ("observations.csv", "wave_fronts.csv", "observations.png"),
    "helical": ("helical_heads.csv", "helical_contacts.csv", "helical_snapshots.csv",
                "helical_heads.png", "helical_wireframes.png"),
    "frf": ("frf.csv", "frf_modes.csv", "frf_bode.png"),
    "bearing": ("bearing_speed.csv", "bearing_speed.png", "bearing_maps.png",
                "bearing_cross_width.csv", "bearing_cross_width.png",
                "bearing_transient.csv", "bearing_transient.png"),
    "orthotropy": ("orthotropy_speeds.csv", "orthotropy_profiles.csv",
                   "orthotropy_bearing.csv", "orthotropy_speeds.png",
                   "orthotropy_profiles.png", "orthotropy_bearing.png"),
    "heads": ("heads_modules.csv", "heads_width.csv", "heads_wraps.csv", "heads_modules.png",
              "heads_width.png", "heads_wraps.png"),
}


def output_files(names: Iterable[str]) -> tuple[str, ...]:
    """The files the studies ``names`` write (``"all"``: every study's); unknown names add
    none (they are refused elsewhere)."""
    names = list(names)
    chosen = list(FILES) if "all" in names else dict.fromkeys(names)
    return tuple(f for name in chosen for f in FILES.get(name, ()))


def check_written(name: str, files: Sequence[Path]) -> list[Path]:
    """``files`` as written by study ``name``, if their names are those of :data:`FILES`;
    else a RuntimeError (the table has drifted from the study's code)."""
    written = tuple(Path(f).name for f in files)
    if written != FILES[name]:
        raise RuntimeError(f"study {name} wrote {written}, but FILES lists {FILES[name]}")
    return list(files)
