//! What `diagnose` and `explain` print of the loop's findings: a diagnosis
//! channel by channel, and the explain loop's rounds. Both paths (the
//! paper's unit and any unit file) print through here.

/// The diagnosis as `diagnose` prints it: each channel's rms, fit and
/// suggestions with its findings, what the records can observe of each
/// effect family (when the sensor says), then what the words used mean.
pub fn print_diagnosis<C: std::fmt::Display>(
    d: &sysid::diagnose::Diagnosis<C, nav_sensors::geometry::Axis>,
) {
    for c in &d.channels {
        println!(
            "{:>3}: validation rms {:.4} deg/h, fit {:.1}%; suggested: {}",
            c.channel,
            c.rms,
            c.compare.val_fit_percent,
            if c.suggested.is_empty() {
                "nothing".to_string()
            } else {
                c.suggested.join(", ")
            }
        );
        for f in &c.findings {
            println!("     {f}");
        }
    }
    if !d.observable.is_empty() {
        println!("what these records can observe:");
        for line in &d.observable {
            println!("  {line}");
        }
    }
    let terms = super::terms::diagnosis_terms(d);
    if !terms.is_empty() {
        println!("terms used above:");
        for t in terms {
            println!("  {t}");
        }
    }
}

/// Every round, then why the loop stopped (and, when it added anything,
/// which coefficient the final table holds).
pub fn print_rounds<C: std::fmt::Display>(
    rounds: &[sysid::explain::Round<C, nav_sensors::geometry::Axis>],
    converged: bool,
    max_rounds: u64,
) {
    for (k, r) in rounds.iter().enumerate() {
        print_round(k, r);
    }
    if converged {
        println!(
            "nothing new suggested: the loop stopped after {} round(s)",
            rounds.len()
        );
    } else {
        println!(
            "stopped at --max-rounds {max_rounds}: the last diagnosis still suggests something (run `dtg-vib diagnose` on the model)"
        );
    }
    if rounds.iter().any(|r| !r.added.is_empty()) {
        println!("{WHICH_COEFFICIENT}");
    }
}

/// Which of an added effect's two coefficients is which: the round's (the
/// diagnosis's statement of its suggestion) and the final table's (the one
/// stored) are one estimator's (issue 23 §3): the same number unless a
/// later round added to the channel.
const WHICH_COEFFICIENT: &str = "coefficients: a round's is the diagnosis's estimate, made as the fit makes it (every row, cross-fitted over 4, 6 and 8 alternating spans, their spread in its interval; its p-value is the ranking's test on the record's two halves); the model below stores and compensates with the fit's: the same number unless a later round added another effect to the channel";

/// Round `k` (from 0): what it added, how each addition is told from its
/// look-alikes, and the validation rms after it.
fn print_round<C: std::fmt::Display>(
    k: usize,
    r: &sysid::explain::Round<C, nav_sensors::geometry::Axis>,
) {
    println!("round {}:", k + 1);
    if k == 0 {
        println!("  fitted with the given effects");
    }
    for x in &r.added {
        println!(
            "  added {}={}: explains {:.0}% of what was left (p {}), coefficient {:.4} ± {:.4} {} (95% CI {:.4} to {:.4}){}",
            x.channel,
            x.effect,
            100.0 * x.err,
            dtg_vib::diagnose::p_text(x.p),
            x.coef,
            x.se,
            x.unit,
            x.ci95[0],
            x.ci95[1],
            if x.alternatives.is_empty() {
                String::new()
            } else {
                format!(
                    "; this record cannot tell it from {}",
                    x.alternatives.join(", ")
                )
            }
        );
    }
    for x in r.added.iter().filter_map(|x| x.separation.as_ref()) {
        println!("    {}", x.advice);
    }
    for x in &r.added {
        for sep in &x.record_separations {
            println!(
                "    {} and {} are collinear on {} alone; {}",
                x.effect,
                sep.effect,
                sep.collinear_on.join(", "),
                if sep.separated_by.is_empty() {
                    "the records together tell them apart".to_string()
                } else {
                    format!("{} told them apart", sep.separated_by.join(", "))
                }
            );
        }
    }
    for x in &r.added {
        for caveat in &x.caveats {
            println!("    caveat on {}={}: {caveat}", x.channel, x.effect);
        }
    }
    let rms: Vec<String> = r
        .channels
        .iter()
        .map(|c| format!("{} {:.4}", c.channel, c.val_rms))
        .collect();
    println!("  validation rms (deg/h): {}", rms.join(", "));
}
