//! Records of one nominal rate are one rate: segments of a log split at its
//! gaps, or two logs, whose median sampling intervals agree within
//! [`sysid::INTERVAL_TOLERANCE`] (0.5 %) fit as one, and a model applies to
//! a record so sampled; beyond it both are refused naming the two
//! intervals. On the crate's example sensor ([`sysid::example::Line`],
//! fixed seeds).

use sysid::example::{Line, Slope, line_record};
use sysid::{FitOptions, INTERVAL_TOLERANCE, Prepared, Signals, SysidError, fit_records};

/// `line_record` with its time stretched by `1 + stretch` (its median step
/// 0.02 × (1 + stretch) s) and shifted to start at `start` s.
fn record(seed: u64, stretch: f64, start: f64) -> Signals {
    let r = line_record(1500, 2.0, seed);
    let t = r.t().iter().map(|t| start + t * (1.0 + stretch)).collect();
    Signals::new(t, r.columns().to_vec()).unwrap()
}

fn options() -> FitOptions<Slope> {
    let mut o = FitOptions::new(1);
    o.recipe.preprocess = Line::preprocess();
    o.recipe.effects[0] = vec![Slope];
    o.recipe.settings.max_centres = 5;
    o
}

#[test]
fn the_tolerance_is_half_a_percent() {
    assert_eq!(INTERVAL_TOLERANCE, 5e-3);
}

#[test]
fn segments_within_half_a_percent_fit_as_one_and_beyond_are_refused() {
    let first = record(1, 0.0, 0.0);
    // The two halves of a real 250 Hz PX4 log differ by 0.3 %; 0.49 % is
    // at the edge.
    for stretch in [0.003, 0.0049] {
        let second = record(2, stretch, 40.0);
        let records = [
            ("log#1".to_string(), &first),
            ("log#2".to_string(), &second),
        ];
        let (model, prepared) = fit_records(&Line, &records, &options(), &|_| {})
            .unwrap_or_else(|e| panic!("{stretch}: {e}"));
        assert_eq!(
            prepared.rows(),
            Prepared::new_many(&Line, &records, &Line::preprocess())
                .unwrap()
                .rows()
        );
        let slope = &model.channel(0).coefficients().unwrap()[0];
        assert!(slope.covers(2.0), "{stretch}: {slope:?}");
    }
    let second = record(2, 0.0051, 40.0);
    let records = [
        ("log#1".to_string(), &first),
        ("log#2".to_string(), &second),
    ];
    let err = Prepared::new_many(&Line, &records, &Line::preprocess()).unwrap_err();
    assert!(matches!(err, SysidError::RecordsDiffer { .. }), "{err}");
    let text = err.to_string();
    assert!(
        text.starts_with(
            "records log#1 and log#2 cannot be fitted together: median sampling interval 0.0199999"
        ) && text.contains(" s against 0.020102"),
        "{text}"
    );
    assert!(
        text.contains("0.51 % apart (at most 0.5 % is one rate)"),
        "{text}"
    );
}

#[test]
fn a_model_checks_a_record_of_its_nominal_rate_and_refuses_another() {
    let train = record(1, 0.0, 0.0);
    let (model, _) = fit_records(&Line, &[("a".to_string(), &train)], &options(), &|_| {}).unwrap();
    for stretch in [-0.0049, 0.003, 0.0049] {
        let other = record(3, stretch, 0.0);
        model
            .prepare(&other)
            .unwrap_or_else(|e| panic!("{stretch}: {e}"));
    }
    for stretch in [-0.0051, 0.0051, 0.25] {
        let err = model.prepare(&record(3, stretch, 0.0)).unwrap_err();
        assert!(
            matches!(err, SysidError::SampleInterval { .. }),
            "{stretch}: {err}"
        );
    }
}

/// `r` without every 60th sample.
fn dropping(r: Signals) -> Signals {
    let keep: Vec<usize> = (0..r.len()).filter(|i| i % 60 != 59).collect();
    let columns = r
        .columns()
        .iter()
        .map(|(n, c)| (n.clone(), keep.iter().map(|&i| c[i]).collect()))
        .collect();
    Signals::new(keep.iter().map(|&i| r.t()[i]).collect(), columns).unwrap()
}

/// A record with dropped samples: every 60th sample missing lengthens its
/// mean interval by 1.7 % but leaves the median. The model keeps the
/// median and compares by it, so a record without drops at the same rate
/// is prepared; its parts round-trip it, and parts without it (a file
/// written before it was stored) read the mean as the median.
#[test]
fn a_model_fitted_on_a_record_with_dropped_samples_compares_by_its_median() {
    let dropped = dropping(record(1, 0.0, 0.0));
    assert!(dropped.dt() / dropped.median_dt() - 1.0 > 0.01);
    let (model, _) =
        fit_records(&Line, &[("d".to_string(), &dropped)], &options(), &|_| {}).unwrap();
    assert!(
        (model.median_dt_s() - 0.02).abs() < 1e-12,
        "{}",
        model.median_dt_s()
    );
    assert!(model.dt_s() / model.median_dt_s() - 1.0 > 0.01);
    model.prepare(&record(3, 0.0, 0.0)).unwrap();

    let again = sysid::Model::from_parts(model.clone().into_parts()).unwrap();
    assert_eq!(again, model);
    let mut old = model.into_parts();
    old.median_dt_s = None;
    let old = sysid::Model::from_parts(old).unwrap();
    assert_eq!(old.median_dt_s(), old.dt_s());
    let err = old.prepare(&record(3, 0.0, 0.0)).unwrap_err();
    assert!(matches!(err, SysidError::SampleInterval { .. }), "{err}");
}

/// Several records fitted together keep the first one's median interval,
/// not that of the records laid end to end (restamped on an even grid at
/// the first one's mean, so its median is that mean): a model of two logs
/// with dropped samples still checks a third log of their rate.
#[test]
fn a_model_of_several_records_keeps_the_first_ones_median() {
    let (a, b) = (
        dropping(record(1, 0.0, 0.0)),
        dropping(record(2, 0.0, 40.0)),
    );
    let records = [("a".to_string(), &a), ("b".to_string(), &b)];
    let (model, _) = fit_records(&Line, &records, &options(), &|_| {}).unwrap();
    assert!(
        (model.median_dt_s() - 0.02).abs() < 1e-12,
        "{}",
        model.median_dt_s()
    );
    model.prepare(&record(3, 0.0, 0.0)).unwrap();
}
