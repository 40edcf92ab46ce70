"""What a validation case module defines (tools/verification/cases/NAME.py):

The harness runs a case's rungs (and option sweep) as one `talus study`; a finished run is a
runner.Run whose `directory` is the variant's folder: its scene, run.log, summary.json and every
output file.

  NAME        short identifier
  TITLE       one line for the report
  SCENE       scene file relative to the repository root (the template)
  LADDER      resolutions (particle spacing dp, or cells) from coarse to fine, at least three
  TOLERANCE   dict resolution -> largest acceptable error (same units as error())
  ERROR_LABEL what error() measures, e.g. "L1 of h / h0" or "front position, relative"
  REFERENCE   where the reference comes from (analytic formula, data file)
  configure(scene: dict, resolution: float, option: dict) -> dict
              returns the scene to run at this resolution with these options
  error(run: runner.Run) -> float
              the error of a finished run against the reference
Optional:
  OPTIONS     dict option-name -> list of values to sweep (each value changes configure())
  EXPECTED_ORDER  observed order of convergence the method promises (reported)
  CONVERGES   False when the error is not controlled by the ladder's resolution (e.g. set by
              the sound speed and h/dp, held fixed): the error must then only stay within the
              tolerance, not fall. Default True: an error that grows with resolution fails.
  gates(run) -> list of (name, passed, value-text): stability gates (no NaN, mass, ...)
  prepare(directory, scene, resolution)  writes files the configured scene names by a path relative to
              `directory`, e.g. a release-thickness raster made for the rung (the harness then names them
              absolutely: every rung runs as a variant of one study, in a folder of its own)
  QUICK_INDEX index of the rung --quick runs (default 0)
  QUICK_END   simulated end time (s) of the --quick run, a short variant of that rung for costly cases
              (it must still cover the part of the run the case is about; gates read run.scene)
  KNOWN_DEVIATION  text: the accuracy tolerance is known not to be met yet (an open issue says
                  why). Such a rung is still run, measured and reported as failing its tolerance,
                  but does not fail the harness; its stability gates still must pass.

A hard case (stability only, no reference solution) sets HARD_CASE = True and defines instead:

  HARD_CASE   True
  NAME, TITLE, SCENE, LADDER (one rung or more: the ladder may be short, a hard case is about a long
              or violent run, not convergence), configure(scene, resolution, option)
  STRESSES    one line: what the case stresses (for the report's "Hard cases" table)
  WORST_LABEL what worst() measures, e.g. "max |rho/rho0 - 1| over the run" (SPH cases: the wcsph
              stage's running maximum, _util.worst_density_deviation) or the case's own measure
              (deepest block interpenetration, largest mass error, ...)
  worst(run) -> float   the worst value of that measure over the whole run (not only at the end)
  TOLERANCE   dict resolution -> largest acceptable worst() (the run fails above it)
  gates(run) -> list of (name, passed, value-text): the stability criteria; each must be able to fail
The case is stable when talus finishes without error, worst() is finite and within TOLERANCE, and
every gate passes; it is not required to converge. REFERENCE and ERROR_LABEL are not needed (the
report says "stability only"); error() defaults to worst().
"""
