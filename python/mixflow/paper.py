"""Li & Zhao (2018): the scenes of Table 1, the constants and the values the paper reports that
the result scripts compare with (report.py, mixture_results.py, liquid_results.py)."""

G = 9.81  # gravity (m/s^2)
D_P = 0.024  # grain diameter (m)
SECTION_X = 1.38  # the section where the Froude number is taken (m)
PROFILE_TIMES = (0.63, 0.75)  # the times of the paper's liquid and granular surfaces (s)

# Table 1 in the paper's order; directory names use '+' for the paper's '&'.
TABLE1 = ["P-I-I", "P-I-II", "P-I-III", "P-I-IV", "P-I-V", "P", "W", "HB", "B", "HB-I", "B-I",
          "W+P", "HB+P", "B+P"]
PAPER_NAME = {s: s.replace("+", "&") for s in TABLE1}
DRY_SERIES = ["P-I-I", "P-I-II", "P-I-III", "P-I-IV", "P-I-V"]  # the runout law's aspect ratios
LIQUIDS = ["W", "HB", "B"]
MIXTURES = ["W+P", "HB+P", "B+P"]

# The paper's numbers (docs/model.md §8): subcritical times after the front's arrival at
# SECTION_X (s), alpha, back-wall surface heights / H, B&P's Savage collisional interval (s),
# stage changes and the start of the outflow (s).
PAPER = {
    "subcritical": {"W": 1.2, "HB": 1.1, "B": 1.0, "W+P": 0.6, "HB+P": 0.3, "B+P": 0.5},
    "alpha": 0.9884,
    "back_wall": {"HB": (0.811, 0.465), "HB+P": (0.997, 0.894)},
    "savage_interval_BP": (0.28, 1.1),
    "liquid_stage_change_s": 2.3,
    "granular_stage_change_s": 0.95,
    "outflow_starts_s": {"W": 1.25, "W+P": 1.39},
}
# The pure liquids' subcritical times, by scene.
PAPER_SUBCRITICAL = {k: PAPER["subcritical"][k] for k in ("W", "HB", "B")}
# The slumps HB-I and B-I: Li & Zhao's time scales (s) and lengths (m) of the normalised fronts.
T_SLUMP = {"HB-I": 4.374e-4, "B-I": 4.376}
L_SLUMP = {"HB-I": 0.5, "B-I": 0.4}
