//! A second plug-in that is not a gyro: two pressure transducers on one
//! manifold, calibrated against a reference in a thermal chamber, one of
//! them with a hysteresis its datasheet does not mention.
//!
//! The simulated test (seeded) steps the reference pressure up and down a
//! staircase while the chamber ramps from 15 to 45 °C. Both transducers
//! read the reference plus a thermal zero shift (known: the fit is told
//! `temp`), a nonlinearity in pressure (left to the network over windows of
//! the reference) and noise; the second also reads +h on levels approached
//! from below and −h on levels approached from above (hidden). A network
//! cannot learn that from the pressure's recent history: on a plateau the
//! window is flat whichever side the level was approached from.
//!
//! The same loop the gyro plug-in runs (fit → diagnose → add → fit) must
//! name the hysteresis on the second transducer only, its 95% interval must
//! cover h, and the second transducer's validation error must fall. The
//! example asserts all three, so it fails under `cargo test` if the loop
//! stops finding what it should.
//!
//! Run it with `cargo run --release -p sysid --example pressure_transducer`.

use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};
use sysid::{
    Candidacy, Effect, OperatingStats, Sensor, SensorError, Separation, Signals, WindowSpec,
    Wording,
};

/// The hidden hysteresis of the second transducer, kPa.
const HYSTERESIS_KPA: f64 = 0.8;
/// The chamber temperature the transducers were trimmed at, °C.
const TRIM_C: f64 = 25.0;
/// A pressure change smaller than this is not a change of direction, kPa.
const DEAD_BAND_KPA: f64 = 1.0;

/// The effects a pressure transducer's error can hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
enum PressureEffect {
    /// Thermal zero shift: kPa per °C away from the trim temperature.
    Temp,
    /// Thermal span shift: per °C, times the pressure in MPa.
    TempSpan,
    /// Hysteresis: +1 on a level approached from below, −1 from above.
    Hyst,
}

impl PressureEffect {
    const ALL: [PressureEffect; 3] = [Self::Temp, Self::TempSpan, Self::Hyst];
}

impl std::fmt::Display for PressureEffect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.id())
    }
}

impl Effect for PressureEffect {
    fn id(&self) -> String {
        match self {
            Self::Temp => "temp",
            Self::TempSpan => "temp_span",
            Self::Hyst => "hyst",
        }
        .into()
    }
    fn unit(&self) -> String {
        match self {
            Self::Temp => "kPa/°C",
            Self::TempSpan => "kPa/(°C·MPa)",
            Self::Hyst => "kPa",
        }
        .into()
    }
    fn description(&self) -> String {
        match self {
            Self::Temp => "thermal zero shift",
            Self::TempSpan => "thermal span shift",
            Self::Hyst => "pressure hysteresis (by the side a level is approached from)",
        }
        .into()
    }
}

/// Transducers `p1`, `p2`, … reading a reference `ref` (kPa) in a chamber
/// at `temp` (°C).
#[derive(Debug, Clone)]
struct Manifold {
    transducers: Vec<String>,
}

/// +1 after the pressure last rose, −1 after it last fell (beyond the dead
/// band); +1 before the first change (the test starts from the bottom).
fn direction(reference: &[f64]) -> Vec<f64> {
    let mut state = 1.0;
    let mut anchor = reference.first().copied().unwrap_or(0.0);
    reference
        .iter()
        .map(|&p| {
            if p > anchor + DEAD_BAND_KPA {
                state = 1.0;
                anchor = p;
            } else if p < anchor - DEAD_BAND_KPA {
                state = -1.0;
                anchor = p;
            }
            state
        })
        .collect()
}

fn column<'a>(rec: &'a Signals, name: &str) -> Result<&'a [f64], SensorError> {
    rec.column(name)
        .ok_or_else(|| format!("the record has no column '{name}'").into())
}

impl Sensor for Manifold {
    type Channel = String;
    type Effect = PressureEffect;
    type Axis = String;

    fn channels(&self) -> Vec<String> {
        self.transducers.clone()
    }

    fn wording(&self) -> Wording {
        Wording {
            target_unit: "kPa".into(),
            operating_unit: "kPa".into(),
            spread: "swing".into(),
            operating_noun: "applied pressure".into(),
            regime_hint: "a pressure-dependent term may be missing".into(),
            slow_hint: "a thermal or ageing drift".into(),
        }
    }

    fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError> {
        Ok(raw.clone())
    }

    fn targets(&self, rec: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
        let reference = column(rec, "ref")?;
        self.transducers
            .iter()
            .map(|p| {
                Ok(column(rec, p)?
                    .iter()
                    .zip(reference)
                    .map(|(p, r)| p - r)
                    .collect())
            })
            .collect()
    }

    fn operating_signals(&self) -> Vec<String> {
        vec!["ref".into()]
    }

    fn operating_scale(&self) -> f64 {
        DEAD_BAND_KPA
    }

    fn extra_columns(&self, rec: &Signals) -> Vec<String> {
        rec.names()
            .into_iter()
            .filter(|n| *n != "ref" && !self.transducers.iter().any(|p| p == n))
            .map(String::from)
            .collect()
    }

    fn candidates(
        &self,
        rec: &Signals,
        samples: &[usize],
        _: usize,
    ) -> Vec<Candidacy<PressureEffect>> {
        let reversals = column(rec, "ref")
            .map(|r| {
                let d = direction(r);
                samples.windows(2).filter(|w| d[w[0]] != d[w[1]]).count()
            })
            .unwrap_or(0);
        PressureEffect::ALL
            .into_iter()
            .map(|e| match e {
                PressureEffect::Hyst if reversals == 0 => Candidacy::NotExcited {
                    effect: e,
                    reason: "the pressure never reverses: every level is approached from one side"
                        .into(),
                },
                _ => Candidacy::Excited(e),
            })
            .collect()
    }

    fn parse_effect(&self, _: usize, id: &str) -> Result<PressureEffect, SensorError> {
        PressureEffect::ALL
            .into_iter()
            .find(|e| e.id() == id)
            .ok_or_else(|| format!("unknown effect '{id}' (valid: temp, temp_span, hyst)").into())
    }

    fn regressors(
        &self,
        rec: &Signals,
        _: usize,
        effects: &[PressureEffect],
    ) -> Result<Vec<Vec<f64>>, SensorError> {
        let (reference, temp) = (column(rec, "ref")?, column(rec, "temp")?);
        let hyst = direction(reference);
        Ok(effects
            .iter()
            .map(|e| match e {
                PressureEffect::Temp => temp.iter().map(|t| t - TRIM_C).collect(),
                PressureEffect::TempSpan => temp
                    .iter()
                    .zip(reference)
                    .map(|(t, p)| (t - TRIM_C) * p / 1000.0)
                    .collect(),
                PressureEffect::Hyst => hyst.clone(),
            })
            .collect())
    }

    fn separation(
        &self,
        _: usize,
        group: &[PressureEffect],
        kappa: &[f64],
        _: &OperatingStats,
    ) -> Separation<String> {
        Separation {
            effects: group.iter().map(Effect::id).collect(),
            combination: group.iter().skip(1).map(Effect::id).zip(kappa.iter().copied()).collect(),
            axis: None,
            responses: vec![None; group.len()],
            advice: "run the staircase at a second chamber temperature, approaching each level from both sides".into(),
        }
    }
}

/// The seeded test: a staircase of 20-s plateaus up to 1000 kPa and back,
/// three times, while the chamber ramps from 15 to 45 °C; at 1 Hz.
fn simulate(seed: u64) -> Signals {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.05).expect("a positive deviation");
    let levels: Vec<f64> = (0..=10)
        .chain((0..10).rev())
        .map(|k| 100.0 * k as f64)
        .collect();
    let staircase: Vec<f64> = (0..3)
        .flat_map(|_| levels.iter().flat_map(|&p| std::iter::repeat_n(p, 20)))
        .collect();
    let n = staircase.len();
    let t: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let temp: Vec<f64> = (0..n).map(|i| 15.0 + 30.0 * i as f64 / n as f64).collect();
    let hyst = direction(&staircase);
    let (mut p1, mut p2) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let (p, dt) = (staircase[i], temp[i] - TRIM_C);
        p1.push(p + 0.05 * dt + 2e-6 * p * p + noise.sample(&mut rng));
        p2.push(p + 0.08 * dt + 1e-6 * p * p + HYSTERESIS_KPA * hyst[i] + noise.sample(&mut rng));
    }
    Signals::new(
        t,
        vec![
            ("p1".into(), p1),
            ("p2".into(), p2),
            ("ref".into(), staircase),
            ("temp".into(), temp),
        ],
    )
    .expect("columns of one length")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let unit = Manifold {
        transducers: vec!["p1".into(), "p2".into()],
    };
    let record = simulate(7);
    let mut options = sysid::FitOptions::new(2);
    options.recipe.preprocess = sysid::Preprocess {
        filter: None,
        window: WindowSpec::new(vec!["ref".into()], 5)?,
        ..sysid::Preprocess::default()
    };
    // The known thermal zero shift; the hysteresis is what the loop must find.
    options.recipe.effects = vec![vec![PressureEffect::Temp]; 2];
    options.recipe.settings.max_centres = 20;
    let e = sysid::explain::explain(
        &unit,
        &[("staircase".into(), &record)],
        &options,
        &sysid::diagnose::DiagnoseOptions::default(),
        4,
        &|_| {},
    )?;

    for (k, round) in e.rounds.iter().enumerate() {
        let rms: Vec<String> = round
            .channels
            .iter()
            .map(|c| format!("{} {:.3} kPa", c.channel, c.val_rms))
            .collect();
        println!("round {}: validation rms {}", k + 1, rms.join(", "));
        for a in &round.added {
            println!(
                "  added {}={} ({}): {:.3} {} (95% CI {:.3} to {:.3})",
                a.channel,
                a.effect,
                PressureEffect::ALL
                    .iter()
                    .find(|e| e.id() == a.effect)
                    .map_or("?".into(), Effect::description),
                a.coef,
                a.unit,
                a.ci95[0],
                a.ci95[1]
            );
        }
    }

    // 1. The loop names the hidden effect, on the channel that has it only.
    let added: Vec<(String, String)> = e
        .rounds
        .iter()
        .flat_map(|r| {
            r.added
                .iter()
                .map(|a| (a.channel.clone(), a.effect.clone()))
        })
        .collect();
    assert_eq!(
        added,
        [("p2".to_string(), "hyst".to_string())],
        "what the loop added"
    );
    assert!(e.converged, "the loop should stop once nothing is left");

    // 2. Its 95% interval (from the final fit) covers the truth.
    let p2 = e.model.channel(1);
    let j = p2
        .effects()
        .iter()
        .position(|x| *x == PressureEffect::Hyst)
        .ok_or("p2's final model lacks hyst")?;
    let c = &p2.coefficients().ok_or("no intervals")?[j];
    println!(
        "p2 hysteresis: {:.3} ± {:.3} kPa (95% CI {:.3} to {:.3}); truth {HYSTERESIS_KPA} kPa",
        c.value, c.se, c.ci95[0], c.ci95[1]
    );
    assert!(
        c.covers(HYSTERESIS_KPA),
        "{c:?} should cover {HYSTERESIS_KPA}"
    );

    // 3. The error falls.
    let before = e.rounds[0].channels[1].val_rms;
    let after = p2.scores().val_rms;
    println!("p2 validation rms {before:.3} → {after:.3} kPa");
    assert!(after < 0.5 * before, "p2's rms {before} → {after}");
    Ok(())
}

/// `cargo test` runs the example (`test = true` builds it with the test
/// harness, which calls this, not `main`).
#[test]
fn names_the_hidden_hysteresis() {
    main().expect("the loop names the hysteresis, its interval covers it, the error falls");
}
