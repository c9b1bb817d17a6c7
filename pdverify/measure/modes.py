"""Natural frequencies of a model's discrete operator against the analytic ones (``pdverify modes``).

The model gives its operator on the free DOFs and its lumped mass (``Model.eigenproblem``: K φ = ω² M φ,
the operator of its transient); the eigenvalues λ = ω² of M⁻¹K nearest zero are computed densely up to
``DENSE_DOFS`` free DOFs, else by ARPACK in shift-invert mode about 0. The reference for every support
pair: the rod and the torsion bar in closed form, the Timoshenko beam from its characteristic determinant
(:mod:`pdverify.exact.vibration`), the Euler-Bernoulli beam from its frequency equation
(:mod:`pdverify.exact.vibration_eb`; also the reference of the higher-order theory, whose slender limit it is).
Modes are matched by order.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..core.errors import InputError, SolveError
from ..core.result import columns_csv, one_line, plain_json
from ..core.scene import HELD, ROD_HELD, Scene
from ..exact.vibration import TimoshenkoBeam, beam_end, rod_frequencies
from ..exact.vibration_eb import eb_frequencies
from ..registry import get_model, models
from ..theory.symbols import frequency_shift

DENSE_DOFS = 300  # up to this many free DOFs a dense eigenvalue solve (every eigenvalue, cheap); ARPACK above
# an eigenvalue below this fraction of ||D K D|| (about 4,500 eps) is zero to round-off: a computed eigenvalue is
# within eps ||A|| times its condition number of the exact one (Bauer-Fike; LAPACK Users' Guide 3rd ed., §4.8), which
# for the paper variants' non-symmetric closures' zero-energy modes is far above eps (docs/cli.md); a true mode this
# small has a round-off estimate over 1e-4 and is warned of by it too
ZERO_EIGENVALUE = 1e-12
ROUNDOFF_WARN = 1e-6  # a mode whose round-off estimate exceeds this carries a warning (as solve's bound does)
TRUE_MODE = 1e-2  # a mode below ZERO_EIGENVALUE whose frequency is the analytic one to this (or its round-off) is
# the beam's own, not a zero-energy mode (a slender strip's first mode: 1.1e-6 off at L/h = 833, fem-timoshenko)


def gives_modes(model) -> bool:
    """Whether ``model`` gives the mass and stiffness of its transient (a ``eigenproblem`` method)."""
    return model.modes


def discrete_eigenvalues(K: sp.spmatrix, mass, count: int) -> tuple[np.ndarray, float]:
    """(λ, ||D K D||_∞, D below): the ``count`` eigenvalues of K φ = λ M φ smallest in modulus, ordered by modulus.
    ``mass``: the lumped mass (a vector), or a consistent mass matrix (sparse, symmetric positive definite; the
    scaling then takes its diagonal: a row sum would add entries of different units where a block couples two kinds
    of unknown).

    The pair is solved as D K D, D M D with D = diag(M)^-1/2 (a congruence: the same eigenvalues), whose entries
    all have the unit of λ, 1/s², whatever the unknowns' units: a rotation's row and a deflection's row of M⁻¹K differ
    by the square of the length unit, so its eigenvalues (and the round-off estimate's norm) would depend on the
    scene's units, where these do not."""
    import scipy.linalg as la
    import scipy.sparse.linalg as spla

    consistent = sp.issparse(mass)
    diag = mass.diagonal() if consistent else np.asarray(mass, float)  # a lumped mass is its own diagonal
    # K / k0 and M / m0 (powers of two: exact) keep every entry an ordinary float whatever the units (a density of
    # 1e-300 overflows 1/M); the eigenvalues are k0 / m0 times those of the scaled pair
    k0 = 2.0 ** np.round(np.log2(abs(K).max()))
    m0 = 2.0 ** np.round(np.log2(np.abs(diag).max()))
    if not np.log2(k0) - np.log2(m0) < 1023:  # k0 / m0 overflows
        raise SolveError(
            "the natural frequencies squared are out of the floating-point range in these units (stiffness "
            f"~{k0:.0e}, mass ~{m0:.0e}); give the scene in units that keep its numbers within about 1e-100..1e100"
        )
    D = sp.diags(1.0 / np.sqrt(diag / m0))
    K = K / k0
    A = sp.csr_matrix(D @ K @ D)
    mass = sp.csr_matrix(D @ (mass / m0) @ D) if consistent else None
    norm = float(abs(A).sum(1).max())
    n = A.shape[0]
    if n <= DENSE_DOFS or count >= n - 1:
        lam = la.eigvals(A.toarray(), mass.toarray()) if consistent else la.eigvals(A.toarray())
    else:  # fixed start vector: the same digits on every run
        v0 = np.random.default_rng(0).standard_normal(n)
        M = sp.csc_matrix(mass) if consistent else None
        lam = spla.eigs(A.tocsc(), k=count, M=M, sigma=0.0, which="LM", return_eigenvectors=False, v0=v0)
    lam = lam[np.argsort(np.abs(lam), kind="stable")][:count]
    return lam * (k0 / m0), norm * (k0 / m0)


def analytic_frequencies(scene: Scene, theory: str, count: int) -> tuple[np.ndarray, str]:
    """The first ``count`` circular frequencies (rad/s) of the continuum the model discretises, and what
    they are."""
    left, right = scene.supports.left, scene.supports.right
    rho = scene.material.density
    if theory == "timoshenko":
        beam = TimoshenkoBeam(
            scene.EI,
            scene.kGA,
            rho * scene.section.A,
            rho * scene.section.I,
            scene.length,
            beam_end(left),
            beam_end(right),
        )
        return beam.frequencies(count), f"Timoshenko beam {left}-{right}: roots of the characteristic determinant"
    if theory in ("euler-bernoulli", "higher-order"):
        ends = beam_end(left), beam_end(right)
        omega = eb_frequencies(scene.EI, rho * scene.section.A, scene.length, *ends, count)
        what = f"Euler-Bernoulli beam {left}-{right}: roots of the frequency equation"
        if theory == "higher-order":  # no closed form of its own: the slender limit, with the theory's distance
            what += " (the higher-order theory's slender limit: it lies below by about Timoshenko's shear and inertia)"
        return omega, what
    if theory == "axial":
        held = (HELD[left][0], HELD[right][0])
        c = np.sqrt(scene.EA / (rho * scene.section.A))
        what = "rod"
    elif theory == "torsion":
        held = (left in ROD_HELD["torsion"], right in ROD_HELD["torsion"])
        c = np.sqrt(scene.material.G * scene.section.J / (rho * scene.section.polar))
        what = "torsion bar"
    else:
        raise InputError(f"modes: no analytic frequencies for theory {theory!r}")
    if not any(held):
        unknown = "twist" if theory == "torsion" else "axial displacement"
        raise InputError(
            f"supports = {left}-{right}: neither end holds the {unknown}, so the {what} has a rigid-body mode; "
            "make one end clamped or pinned"
        )
    form = "k pi c / L" if all(held) else "(k - 1/2) pi c / L"
    return rod_frequencies(scene.length, c, held, count), f"{what} {left}-{right}: {form}"


@dataclass
class ModeTable:
    """The first modes of a model's operator beside the analytic ones."""

    scene: str
    model: str
    parameters: dict
    dofs: int
    reference: str
    eigenvalues: np.ndarray  # λ = ω² of M⁻¹K (complex)
    analytic: np.ndarray  # ω (rad/s)
    roundoff: np.ndarray  # relative round-off estimate of each frequency
    warnings: list = field(default_factory=list)
    nonlocal_shift: np.ndarray | None = None  # the continuum's own shift at the model's horizon (None: none known)
    horizon: float | None = None  # delta of that shift
    ignored: str = ""  # what of the scene plays no part in its free vibration (a yield stress, a load path)

    @property
    def omega(self) -> np.ndarray:
        """Re √λ (rad/s)."""
        return np.sqrt(self.eigenvalues.astype(complex)).real

    def columns(self) -> dict:
        return {
            "mode": np.arange(1, len(self.analytic) + 1),
            "frequency_hz": self.omega / (2 * np.pi),
            "analytic_hz": self.analytic / (2 * np.pi),
            "rel_error": self.omega / self.analytic - 1.0,
            **({} if self.nonlocal_shift is None else {"nonlocal": self.nonlocal_shift}),
            "roundoff": self.roundoff,
        }

    @property
    def notes(self) -> list[str]:
        """What the table's columns mean where that is not plain."""
        out = [self.ignored] if self.ignored else []
        if self.nonlocal_shift is None:
            return out
        return out + [
            f"nonlocal: the shift of the model's continuum at its horizon delta = {self.horizon:.6g} (the operator's "
            "symbol; exact for sine modes, the bulk wave's otherwise): the model's own error, which the grid does not "
            "remove at a fixed delta; rel_error - nonlocal is the grid's"
        ]

    def to_csv(self) -> str:
        head = [f"# {n}" for n in self.notes] + [f"# warning: {w}" for w in self.warnings]
        return "".join(f"{one_line(line)}\n" for line in head) + columns_csv(self.columns(), fmt="%.12g")

    def to_json(self) -> str:
        cols = self.columns()
        rows = [{k: v[i] for k, v in cols.items()} for i in range(len(self.analytic))]
        for r, lam in zip(rows, self.eigenvalues):
            r["eigenvalue"] = [lam.real, lam.imag]
        doc = {
            "scene": self.scene,
            "model": self.model,
            "parameters": self.parameters,
            "dofs": self.dofs,
            "reference": self.reference,
            "modes": rows,
            "notes": self.notes,
            "warnings": self.warnings,
        }
        return json.dumps(plain_json(doc), indent=1)

    def to_table(self) -> str:
        lines = [f"# scene: {self.scene}   model: {self.model}   free dofs: {self.dofs}"]
        lines.append("# parameters: " + ", ".join(f"{k}={v}" for k, v in self.parameters.items()))
        lines.append(f"# reference: {self.reference}")
        lines += [f"# {n}" for n in self.notes]
        lines += [f"# warning: {w}" for w in self.warnings]
        lines = [one_line(line) for line in lines]
        cols = self.columns()
        lines.append(f"{'mode':>5}" + "".join(f"{n:>16}" for n in list(cols)[1:]))
        for i in range(len(self.analytic)):
            lines.append(f"{i + 1:5d}" + "".join(f"{float(cols[c][i]):16.8g}" for c in list(cols)[1:]))
        return "\n".join(lines) + "\n"


def modes(scene: Scene, model: str, given: dict, count: int) -> ModeTable:
    """The first ``count`` natural frequencies of ``model``'s discrete operator on ``scene`` (its supports,
    section and material; loads and [dynamics] play no part) against the analytic ones."""
    m = get_model(model)
    if not gives_modes(m):
        can = ", ".join(n for n, x in models().items() if gives_modes(x))
        raise InputError(f"model {m.name}: gives no mass and stiffness operator for natural frequencies; use {can}")
    if count < 1:
        raise InputError(f"--count {count}: give a number of modes, 1 or more")
    if "continuum" in given and m.option("continuum") and m.option("continuum").coerce(m.name, given["continuum"]):
        raise InputError(
            "continuum = true: modes gives the frequencies of the discrete operator, and its nonlocal column the "
            "shift of the continuum at the horizon; drop continuum (a static solve takes it)"
        )
    if (
        "continuum_m" in given
        and m.option("continuum_m")
        and m.option("continuum_m").coerce(m.name, given["continuum_m"])
    ):
        raise InputError(
            f"continuum_m = {given['continuum_m']}: sets the levels of a static solve's continuum, which modes does "
            "not compute (its nonlocal column is the continuum's closed-form shift); drop continuum_m"
        )
    if scene.material.density is None:
        raise InputError("material.density: needed for natural frequencies; add density to the scene")
    beyond = [
        what
        for what, present in (
            ("an elastic end (spring)", any(scene.supports.kind(side) == "spring" for side in ("left", "right"))),
            ("supports.inner", bool(scene.supports.inner)),
            ("segments", bool(scene.segments)),
        )
        if present
    ]
    if beyond:
        raise InputError(
            f"{', '.join(beyond)}: the analytic frequencies modes compares with are those of a uniform beam held at "
            "its ends by named supports; drop them for natural frequencies"
        )
    elastic = scene.material.model_copy(update={"yield_stress": None, "failure_strain": None})
    # the free vibration of the supported, unloaded beam: elastic (a yield stress or a failure strain plays no part)
    bare = scene.model_copy(update={"loads": [], "dynamics": None, "loading": None, "material": elastic})
    found = m.check(bare)
    if found:
        raise InputError(found)
    params = m.resolve(bare, given)
    if found := m.refusals(bare, params):  # what the variant does not define on these supports
        raise InputError(found)
    K, mass = m.eigenproblem(bare, params)
    if count > K.shape[0]:
        raise InputError(f"--count {count}: the operator has {K.shape[0]} free DOFs; use fewer modes or more points")
    analytic, reference = analytic_frequencies(scene, m.theory, count)
    lam, norm = discrete_eigenvalues(K, mass, count)
    # Bauer-Fike with a well-conditioned eigenbasis: |dλ| <= eps ||M⁻¹K||, half of it relative in ω
    roundoff = 0.5 * np.finfo(float).eps * norm / np.abs(lam)
    warnings = []
    zero = ZERO_EIGENVALUE * norm  # below it an eigenvalue's sign and imaginary part are the rounding's
    omega = np.sqrt(lam.astype(complex)).real
    for k, v in enumerate(lam):
        if abs(v) <= zero and abs(omega[k] / analytic[k] - 1.0) <= TRUE_MODE:
            continue  # a true mode below the line (a slender Timoshenko beam: ||D K D|| is its shear modes'), its
            # frequency the analytic one; its round-off estimate warns of itself below
        if abs(v) <= zero:
            warnings.append(
                f"mode {k + 1}: the eigenvalue of M^-1 K is zero to round-off (below {ZERO_EIGENVALUE:g} ||D K D||) "
                "and its frequency is not the analytic one: a mode of zero energy (the boundary closures); its "
                "frequency is 0 to round-off"
            )
        elif v.real <= 0 or abs(v.imag) > max(1e-9 * abs(v), zero):
            warnings.append(
                f"mode {k + 1}: the eigenvalue {v.real:.6g}{v.imag:+.3g}j of M^-1 K is not real positive (the boundary "
                "closures); its frequency is Re sqrt(eigenvalue)"
            )
    if m.theory == "higher-order":  # the reference is the slender limit: say how far the theory lies from it
        tim, _ = analytic_frequencies(scene, "timoshenko", count)
        gap = np.abs(tim / analytic - 1)
        if gap.max() > 1e-4:
            warnings.append(
                f"reference: the Euler-Bernoulli frequencies are the higher-order theory's slender limit; on this "
                f"beam shear and rotary inertia lower them by about {gap.max():.1e} (Timoshenko's beam, mode "
                f"{int(np.argmax(gap)) + 1}), a difference of theories, not of the grid"
            )
    worst = int(np.argmax(roundoff))
    if roundoff[worst] > ROUNDOFF_WARN:
        warnings.append(
            f"mode {worst + 1}: round-off may reach {roundoff[worst]:.1e} of the frequency (eps ||D K D|| / "
            "eigenvalue); use fewer points"
        )
    table = ModeTable(scene.name, m.name, params, K.shape[0], reference, lam, analytic, roundoff, warnings)
    dropped = [k for k in ("yield_stress", "failure_strain") if getattr(scene.material, k) is not None]
    dropped += ["[loading]"] if scene.loading is not None else []
    if dropped:
        table.ignored = f"{', '.join(dropped)}: not part of the free vibration of the unloaded beam, which is elastic"
    if getattr(m, "dispersion", "") and params.get("horizon") is not None:
        table.horizon = m.delta(bare, params)
        table.nonlocal_shift = frequency_shift(m.dispersion, wave_numbers(scene, m.theory, analytic), table.horizon)
    return table


def wave_numbers(scene: Scene, theory: str, omega: np.ndarray) -> np.ndarray:
    """The wave number k of each analytic frequency: ω = k² sqrt(EI / ρA) of a beam, ω = c k of a rod or torsion
    bar."""
    rho = scene.material.density
    if theory == "axial":
        return omega / np.sqrt(scene.EA / (rho * scene.section.A))
    if theory == "torsion":
        return omega / np.sqrt(scene.material.G * scene.section.J / (rho * scene.section.polar))
    return np.sqrt(omega) * (rho * scene.section.A / scene.EI) ** 0.25
