//! The residual's correlation tests: whiteness beyond the model's memory,
//! independence of every input, and the Billings–Voon nonlinear tests of
//! the operating signals, on the rows far enough from a record's ends.

use super::NamedCheck;
use super::context::Context;
use crate::residuals::{billings_voon, independence, whiteness_beyond};

/// The tests of a validation residual, and the names of those that fail.
pub(super) fn correlation_checks(
    residual: &[f64],
    ctx: &Context,
    opts: &super::DiagnoseOptions,
) -> (Vec<NamedCheck>, Vec<String>) {
    let mut checks = Vec::new();
    let steady = |x: &[f64]| -> Vec<f64> { ctx.steady.iter().map(|&i| x[i]).collect() };
    let e = steady(residual);
    let dec: Vec<f64> = e.iter().step_by(ctx.decimation).copied().collect();
    let lag = opts
        .max_lag
        .min(dec.len().saturating_sub(ctx.memory + 2) / 4)
        .max(1);
    if dec.len() > ctx.memory + lag + 2 {
        checks.push(NamedCheck {
            name: "whiteness".into(),
            check: whiteness_beyond(&dec, ctx.memory, lag, opts.confidence),
        });
    }
    let lag = opts.max_lag.min(e.len() / 4).max(1);
    // Operating signals by name, extra columns as `col:NAME` (the effect id
    // a column would have).
    let inputs = ctx
        .operating
        .iter()
        .map(|(n, v)| (n.clone(), steady(v), true))
        .chain(
            ctx.extras
                .iter()
                .map(|(n, v)| (format!("col:{n}"), steady(v), false)),
        );
    for (name, u, operating) in inputs {
        checks.push(NamedCheck {
            name: format!("independence:{name}"),
            check: independence(&e, &u, lag, opts.confidence),
        });
        if operating {
            for c in billings_voon(&e, &u, lag.min(10), opts.confidence) {
                checks.push(NamedCheck {
                    name: format!("{}:{name}", c.kind.name()),
                    check: c,
                });
            }
        }
    }
    let failing: Vec<String> = checks
        .iter()
        .filter(|c| !c.check.passed)
        .map(|c| c.name.clone())
        .collect();
    (checks, failing)
}
