#!/usr/bin/python3
"""Where an experiment's error lives: for each technique at the table's equal-sample budget,
the share of the squared error held by the worst 0.1 % and 1 % of pixels, and σ/µ with those
pixels left out (worst pixels chosen per image, mean over seeds). A σ/µ dominated by a few
pixels measures rare bright paths, not the bulk of the image; the TAIS analysis
(results/tais/analysis.md) uses this to say which paths a map could not steer.

    experiments/error_concentration.py results/tais/fig07_scatter_direction.json [--spp N]
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from harness import paths, records, results  # noqa: E402
from harness.plots import read_rgb  # noqa: E402
from harness.records import SPP, TechniqueBudget  # noqa: E402


def concentration(image: np.ndarray, reference: np.ndarray) -> dict[str, float]:
    squared = ((image - reference) ** 2).mean(axis=2).ravel()
    order = np.sort(squared)[::-1]
    total = order.sum()
    mean = reference.mean()
    out = {"sigma_over_mu": float(np.sqrt(squared.mean()) / mean)}
    for fraction, name in ((0.001, "0.1%"), (0.01, "1%")):
        k = max(1, int(len(order) * fraction))
        out[f"share_{name}"] = float(order[:k].sum() / total)
        out[f"sigma_over_mu_without_{name}"] = float(np.sqrt(order[k:].mean()) / mean)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results")
    parser.add_argument("--spp", type=int, help="budget (default: the table's)")
    args = parser.parse_args()
    doc = results.read(Path(args.results))
    spp = args.spp or doc.table.spp
    reference = read_rgb(paths.output(doc.reference.file))
    keys = ["sigma_over_mu", "share_0.1%", "sigma_over_mu_without_0.1%", "share_1%",
            "sigma_over_mu_without_1%"]
    print(f"{doc.experiment} ({doc.profile}), {spp} spp, mean over "
          f"{len(doc.seeds)} seeds\n")
    print("| technique | σ/µ | worst 0.1 % share | σ/µ without them | worst 1 % share "
          "| σ/µ without them |")
    print("|---|---|---|---|---|---|")
    runs = records.group_by_key(doc.runs)
    for technique in doc.techniques:
        at_budget = runs.get(TechniqueBudget(technique, SPP, spp))
        if not at_budget:
            continue
        rows = [concentration(read_rgb(paths.output(r.file)), reference) for r in at_budget]
        means = [np.mean([row[k] for row in rows]) for k in keys]
        print(f"| {technique} | {means[0]:.3g} | {means[1]:.0%} | {means[2]:.3g} | "
              f"{means[3]:.0%} | {means[4]:.3g} |")


if __name__ == "__main__":
    main()
