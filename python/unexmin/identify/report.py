"""report.md and its plots: the identified parameters and, per degree of freedom, the measured
inertial term against the model's forces with the identified and the nominal parameters."""

import numpy as np

from unexmin.identify.model import DOF, INDEX

UNITS = ("N", "N", "N", "N m", "N m", "N m")


def inertial_terms(fit, x):
    """Measured side of each equation with parameters x: (m + m_VBS + m_A) D2[x] [N] (world frame)
    and (I + I_A) dw [N m] (body frame), m = rho V - buoyancy."""
    s, p = fit.problem.s, fit.problem.p
    mass = s.water_density * p.hydro.volume - x[INDEX["buoyancy_kg"]] + x[INDEX["added_mass"]] + s.vbs_nav[s.keep]
    inertia = p.hydro.inertia + np.array([x[INDEX[f"added_inertia_{d}"]] for d in DOF[3:]])
    return np.hstack([mass[:, None] * s.acc[s.keep], inertia * s.dw[s.keep]])


def write_plots(out_dir, fit, nominal):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = fit.problem.s.t[fit.problem.s.keep]
    measured = inertial_terms(fit, fit.x)
    model = measured - fit.problem.residual(fit.x)
    model_nominal = inertial_terms(fit, nominal) - fit.problem.residual(nominal)
    files = []
    for k, dof in enumerate(DOF):
        fig, ax = plt.subplots(figsize=(8, 3.2))
        ax.plot(t, measured[:, k], color="k", lw=1.6, label="measured (inertia x acceleration)")
        ax.plot(t, model[:, k], color="tab:blue", lw=1.0, label="model, identified")
        ax.plot(t, model_nominal[:, k], color="tab:orange", lw=0.8, ls="--", label="model, nominal")
        ax.set_xlabel("mission time [s]")
        ax.set_ylabel(f"{dof} [{UNITS[k]}]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
        fig.tight_layout()
        name = f"fit_{dof}.png"
        fig.savefig(out_dir / name, dpi=90)
        plt.close(fig)
        files.append(name)
    return files


def write(out_dir, data, fit, nominal, signals):
    """report.md (+ fit_<dof>.png) in out_dir."""
    plots = write_plots(out_dir, fit, nominal)

    def cell(v, s):
        return f"{v:.5g} ± {s:.2g}" if s is not None else f"{v:.5g} (not identified)"

    rows = [
        ("buoyancy [kg]", data["buoyancy_kg"]["value"], data["buoyancy_kg"]["sigma"], nominal[INDEX["buoyancy_kg"]])
    ]
    for i, a in enumerate("xyz"):
        rows.append((f"cog {a} [m]", data["cog_m"]["value"][i], data["cog_m"]["sigma"][i], nominal[INDEX[f"cog_{a}"]]))
    for kind, unit in (("quadratic", "N s²/m², N m s²/rad²"), ("linear", "N s/m, N m s/rad")):
        for i, d in enumerate(DOF):
            e = data[f"damping_{kind}"]
            rows.append(
                (f"{kind} damping {d} [{unit}]", e["value"][i], e["sigma"][i], nominal[INDEX[f"damping_{kind}_{d}"]])
            )
    for g in ("horizontal", "vertical"):
        e = data["thrust_gain"]
        rows.append((f"thrust gain {g} (thrusters {e['groups'][g]})", e["value"][g], e["sigma"][g], 1.0))
    rows.append(
        ("added mass [kg]", data["added_mass"]["value"], data["added_mass"]["sigma"], nominal[INDEX["added_mass"]])
    )
    for i, d in enumerate(DOF[3:]):
        rows.append(
            (
                f"added inertia {d} [kg m²]",
                data["added_inertia"]["value"][i],
                data["added_inertia"]["sigma"][i],
                nominal[INDEX[f"added_inertia_{d}"]],
            )
        )
    lines = [
        f"# Identification of {data['robot']} from `{data['bag']}`",
        "",
        "Model, method and what a mission must excite: docs/identification.md. σ is 1σ from the fit's "
        "Jacobian; a parameter the bag cannot pin down keeps the description's value and is listed as "
        "not identified.",
        "",
        "| parameter | identified | nominal (description) |",
        "| --- | --- | --- |",
    ]
    lines += [f"| {name} | {cell(v, s)} | {n:.5g} |" for name, v, s, n in rows]
    lines += [
        "",
        f"Not identified by this bag: {', '.join(data['unidentifiable']) or 'none'}.",
        f"Fixed by request: {', '.join(data['fixed']) or 'none'}.",
        "",
        "## Fit",
        "",
        f"{data['fit']['samples']} navigation samples of {data['fit']['navigation_period_s']:.3g} s, "
        f"Savitzky-Golay window {data['fit']['window_s']:.3g} s, {data['fit']['wall_time_s']} s of wall time.",
        "",
        "| degree of freedom | residual RMS, identified | residual RMS, nominal |",
        "| --- | --- | --- |",
    ]
    for k, d in enumerate(DOF):
        lines.append(
            f"| {d} [{UNITS[k]}] | {data['fit']['residual_rms'][d]:.4g} | "
            f"{data['fit']['residual_rms_nominal'][d]:.4g} |"
        )
    lines += [
        "",
        "Measured inertial term against the model's forces, per degree of freedom (surge, sway, "
        "heave in the world frame; roll, pitch, yaw in the body frame):",
        "",
    ]
    lines += [f"![{p}]({p})" for p in plots]
    (out_dir / "report.md").write_text("\n".join(lines) + "\n")
