"""Named, runnable studies: ``gfbopt run problems/NAME.toml`` → ``results/NAME/``.

A study file gives its source (full citation, table or figure), its inputs, the published
values where there are any and a tolerance per compared quantity.  It is validated against
the schema of its kind before anything is solved (:mod:`.spec`).

======================  ===================================================================
module                  responsibility
======================  ===================================================================
:mod:`.spec`            the schema of every study kind, one vocabulary (glossary names)
:mod:`.base`            validated study, result of a run, model building, labels for people
:mod:`.tables`          static_table, profile, grid_convergence, concentric_impedance
:mod:`.sweeps`          load_sweep, linear_coefficients (a bearing file in SI)
:mod:`.maps`            linear_map, transient_map, transient_points (stability)
:mod:`.transients`      orbits, bifurcation
:mod:`.design`          pitch_design (bump foil chosen for rotor stability)
:mod:`.stability`       onset_conventions (onset speed against the film convention)
:mod:`.damping`         loss_factor_map (loss factor η against compliance S)
:mod:`.doe`             sweep (sampled studies into a Parquet store; resume, Dask)
:mod:`.running_points`  points at the running condition ([journal]/[thermal] files)
:mod:`.onset_status`    the onset_status of an onset row
:mod:`.checks`          internal checks and comparisons with published values
:mod:`.report`          CSV, figures, summary.json, README per study, RESULTS/index.md
:mod:`.output`          where results may be written: safe names, no symlink escape, atomic
:mod:`.runner`          load_study, study_from_dict, compute, run_study
======================  ===================================================================
"""
from .base import Study, StudyResult
from .report import summary_line, write_index, write_result
from .runner import KINDS, LoadedStudy, compute, load_study, run_study, study_from_dict
from .spec import SCHEMAS, validate

__all__ = ["KINDS", "LoadedStudy", "SCHEMAS", "Study", "StudyResult", "compute", "load_study",
           "run_study", "study_from_dict", "summary_line", "validate", "write_index",
           "write_result"]
