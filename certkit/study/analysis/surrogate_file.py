"""The study's surrogates in a file of their own (JSON), for use outside the report.

``certkit study export STUDY.yaml --surrogates FILE`` writes it, ``certkit study predict FILE`` and
:func:`certkit.study.load_surrogates` read it. Each response's kept model is stored in the report page's export
format (:mod:`.export`: polynomial, MLP or Gaussian process with its input bounds), with its goodness of fit;
the possible-design classifier (logistic regression on polynomial features, :mod:`.validity`) is stored as its
powers, scaling and coefficients. Evaluation here is vectorised numpy with the same arithmetic. A handling-quality
level derived from the mode quantities (:mod:`.derived_levels`; version 2) is stored as the responses it comes from,
and read as the rule's level function of their predictions.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Union

import numpy as np

from certkit.errors import UserError
from certkit.study.analysis.derived_levels import DerivedLevel, level_of_margins, mode_offers
from certkit.study.analysis.export import export_surrogate
from certkit.study.analysis.surrogates import Surrogate
from certkit.study.analysis.validity import Validity
from certkit.study.spec import Study

#: a JSON object of the file
Document = dict[str, Any]
#: designs: an array of rows (SI), one mapping {path: value} or a list of them
Points = Union[np.ndarray, Sequence[Sequence[float]], Mapping[str, float], Sequence[Mapping[str, float]]]

FORMAT = "certkit-surrogates"
VERSION = 2
#: versions this certkit reads (version 1 has no derived levels)
READABLE = (1, 2)


def _validity_doc(validity: Validity | None) -> Document | None:
    if validity is None or validity.estimator is None:
        return None
    features, scaler, logistic = (step for _, step in validity.estimator.steps)
    return {
        "lo": validity.bounds[:, 0].tolist(),
        "hi": validity.bounds[:, 1].tolist(),
        "powers": features.powers_.tolist(),
        "mean": scaler.mean_.tolist(),
        "scale": scaler.scale_.tolist(),
        "coef": np.ravel(logistic.coef_).tolist(),
        "intercept": float(np.ravel(logistic.intercept_)[0]),
        "note": validity.note,
    }


def surrogates_document(
    study: Study,
    surrogates: dict[str, Surrogate],
    validity: Validity | None = None,
    sha256: str = "",
    levels: dict[str, DerivedLevel] | None = None,
) -> Document:
    """The file's content: the study's variables, objectives and constraints, every kept model and its fit, the
    derived levels."""
    responses: Document = {}
    for name, s in surrogates.items():
        responses[name] = {
            "model": export_surrogate(s),
            "label": s.kept.label,
            "selection": s.selection,
            "cv_r2": s.cv.r2,
            "cv_rmse": s.cv.rmse,
            "validation_r2": s.validation.r2,
            "validation_rmse": s.validation.rmse,
            "n_training": s.n_training,
            "n_validation": s.n_validation,
            "flagged": s.flagged,
        }
    for name, d in (levels or {}).items():
        responses[name] = {
            "derived": {
                "mode": d.source.mode,
                "configuration": d.source.configuration,
                "kind": d.source.kind,
                "from": d.source.sources,
            },
            "label": d.kept.label,
            "validation_agreement": d.agreement,
            "n_validation": d.n_validation,
            "flagged": d.flagged,
        }
    return {
        "format": FORMAT,
        "version": VERSION,
        "study": study.name,
        "sha256": sha256,
        "variables": [
            {"path": v.path, "lower": v.lower, "upper": v.upper, "baseline": v.baseline, "unit_label": v.unit_label}
            for v in study.variables
        ],
        "objectives": [o.model_dump() for o in study.objectives],
        "constraints": [c.model_dump() for c in study.constraints],
        "responses": responses,
        "validity": _validity_doc(validity),
    }


def write_surrogates(path: str | Path, document: Document) -> Path:
    path = Path(path)
    path.write_text(json.dumps(document, indent=1, allow_nan=True), encoding="utf-8")
    return path


def _unit(doc: Document, x: np.ndarray) -> np.ndarray:
    lo, hi = np.asarray(doc["lo"], dtype=float), np.asarray(doc["hi"], dtype=float)
    return np.asarray((x - lo) * (2.0 / (hi - lo)) - 1.0)


def evaluate_model(doc: Document, x: np.ndarray) -> np.ndarray:
    """An exported model (:mod:`.export` format) at the rows of ``x`` (SI), vectorised."""
    u = _unit(doc, np.atleast_2d(np.asarray(x, dtype=float)))
    kind = doc["kind"]
    if kind == "polynomial":
        y = np.full(len(u), doc["intercept"])
        for coef, term in zip(doc["coef"], doc["terms"]):
            prod = np.full(len(u), coef)
            for i, p in term:
                prod = prod * u[:, i] ** p
            y = y + prod
    elif kind == "mlp":
        h = u
        for k, (w, b) in enumerate(zip(doc["weights"], doc["biases"])):
            z = h @ np.asarray(w) + np.asarray(b)
            h = np.tanh(z) if k < len(doc["weights"]) - 1 else z
        y = h[:, 0] * doc["scale"] + doc["mean"]
    elif kind == "gp":
        d = (u[:, None, :] - np.asarray(doc["x"])[None, :, :]) / np.asarray(doc["length_scale"])
        y = doc["mean"] + doc["std"] * (np.exp(-0.5 * np.sum(d**2, axis=2)) * doc["constant"]) @ np.asarray(
            doc["alpha"]
        )
    else:
        raise ValueError(f"unknown model kind {kind!r}")
    return np.asarray(np.exp(y) if doc["log"] else y)


@dataclass
class SurrogateSet:
    """Surrogates read from a file: ``predict`` the responses at designs, ``possible`` the validity classifier."""

    document: Document

    @property
    def variables(self) -> list[str]:
        return [v["path"] for v in self.document["variables"]]

    @property
    def responses(self) -> list[str]:
        return list(self.document["responses"])

    def inputs(self, points: Points) -> np.ndarray:
        """Rows in the variables' order (SI) from an array, or a mapping / list of mappings {path: value}
        (a variable not given takes its baseline)."""
        if isinstance(points, Mapping):
            points = [points]
        if isinstance(points, list) and points and isinstance(points[0], Mapping):
            unknown = sorted({k for p in points for k in p} - set(self.variables))
            if unknown:
                raise UserError(
                    f"not a variable of these surrogates: {', '.join(unknown)} (variables: {', '.join(self.variables)})"
                )
            base = {v["path"]: v["baseline"] for v in self.document["variables"]}
            return np.array([[float(p.get(path, base[path])) for path in self.variables] for p in points])
        x = np.atleast_2d(np.asarray(points, dtype=float))
        if x.shape[1] != len(self.variables):
            raise UserError(
                f"expected {len(self.variables)} values per design ({', '.join(self.variables)}), got {x.shape[1]}"
            )
        return x

    def predict(self, points: Points, responses: list[str] | None = None) -> dict[str, np.ndarray]:
        x = self.inputs(points)
        names = responses or self.responses
        unknown = [r for r in names if r not in self.document["responses"]]
        if unknown:
            raise UserError(f"no surrogate for {', '.join(unknown)} (responses: {', '.join(self.responses)})")
        out = {}
        for r in names:
            entry = self.document["responses"][r]
            if "derived" in entry:
                out[r] = self._level(entry["derived"], x)
            else:
                out[r] = evaluate_model(entry["model"], x)
        return out

    def _level(self, derived: Document, x: np.ndarray) -> np.ndarray:
        """A derived level: the best level whose least margin is predicted ≥ 0 (kind "margins"), or the rule's level
        function (:func:`.derived_levels.mode_offers`) of the predicted quantities."""
        if derived.get("kind") == "margins":
            return level_of_margins(
                {lv: evaluate_model(self.document["responses"][r]["model"], x) for lv, r in derived["from"].items()}
            )
        offer = mode_offers().get(derived["mode"])
        if offer is None or offer.level is None:
            raise UserError(f"no installed rule gives the level of the mode {derived['mode']!r}")
        q = {kw: evaluate_model(self.document["responses"][r]["model"], x) for kw, r in derived["from"].items()}
        return np.asarray(offer.level(derived["mode"], derived["configuration"], **q), dtype=float).ravel()

    def possible(self, points: Points) -> np.ndarray:
        """Designs classed as possible aircraft (every design when the study had no impossible case)."""
        x = self.inputs(points)
        doc = self.document.get("validity")
        if not doc:
            return np.ones(len(x), dtype=bool)
        u = _unit(doc, x)
        features = np.column_stack([np.prod(u ** np.asarray(p), axis=1) for p in doc["powers"]])
        z = (features - np.asarray(doc["mean"])) / np.asarray(doc["scale"])
        return np.asarray(z @ np.asarray(doc["coef"]) + doc["intercept"] <= 0.0)


def load_surrogates(path: str | Path) -> SurrogateSet:
    """Read a surrogates file written by ``certkit study export --surrogates``."""
    try:
        document = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise UserError(f"{path}: cannot read a surrogates file ({exc})") from None
    if not isinstance(document, dict) or document.get("format") != FORMAT:
        raise UserError(f"{path}: not a certkit surrogates file (written by `certkit study export --surrogates`)")
    if document.get("version") not in READABLE:
        raise UserError(
            f"{path}: surrogates file version {document.get('version')!r}; this certkit reads "
            + ", ".join(map(str, READABLE))
        )
    return SurrogateSet(document)
