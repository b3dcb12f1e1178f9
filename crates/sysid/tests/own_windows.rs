//! Channels whose own operating signals differ (an inertial unit of several
//! IMUs: each gyro its own IMU's accelerometers) each read a window of
//! their own signals by default, and a named window is every channel's.

use sysid::example::{Line, Slope, line_record};
use sysid::{
    Candidacy, FitOptions, OperatingStats, Sensor, SensorError, Separation, Signals, WindowSpec,
    Wording,
};

/// Two [`Line`]s side by side: channel `y` follows `u`, channel `y2`
/// follows `v`, each its own operating signal.
#[derive(Debug, Clone, Copy)]
struct TwoLines;

const OWN: [(&str, &str); 2] = [("y", "u"), ("y2", "v")];

impl Sensor for TwoLines {
    type Channel = String;
    type Effect = Slope;
    type Axis = String;

    fn channels(&self) -> Vec<String> {
        OWN.iter().map(|(y, _)| y.to_string()).collect()
    }
    fn wording(&self) -> Wording {
        Line.wording()
    }
    fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError> {
        Ok(raw.clone())
    }
    fn targets(&self, calibrated: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
        OWN.iter()
            .map(|(y, _)| Ok(calibrated.column(y).ok_or("no target")?.to_vec()))
            .collect()
    }
    fn operating_signals(&self) -> Vec<String> {
        vec!["u".into()]
    }
    fn operating_signals_of(&self, channel: usize) -> Vec<String> {
        vec![OWN[channel].1.into()]
    }
    fn operating_scale(&self) -> f64 {
        Line.operating_scale()
    }
    fn extra_columns(&self, _: &Signals) -> Vec<String> {
        Vec::new()
    }
    fn candidates(&self, _: &Signals, _: &[usize], _: usize) -> Vec<Candidacy<Slope>> {
        vec![Candidacy::Excited(Slope)]
    }
    fn parse_effect(&self, _: usize, id: &str) -> Result<Slope, SensorError> {
        Line.parse_effect(0, id)
    }
    fn regressors(
        &self,
        calibrated: &Signals,
        channel: usize,
        effects: &[Slope],
    ) -> Result<Vec<Vec<f64>>, SensorError> {
        let u = calibrated.column(OWN[channel].1).ok_or("no input")?;
        Ok(effects.iter().map(|_| u.to_vec()).collect())
    }
    fn separation(&self, k: usize, g: &[Slope], c: &[f64], o: &OperatingStats) -> Separation {
        Line.separation(k, g, c, o)
    }
}

/// A record of both lines: `y`, `u` as [`line_record`] of seed 1, `y2`,
/// `v` as its record of seed 2 and another slope.
fn record(n: usize) -> (Signals, Signals) {
    let one = line_record(n, 2.0, 1);
    let two = line_record(n, -1.0, 2);
    let col = |r: &Signals, c: &str| r.column(c).unwrap().to_vec();
    let both = Signals::new(
        one.t().to_vec(),
        vec![
            ("y".into(), col(&one, "y")),
            ("u".into(), col(&one, "u")),
            ("y2".into(), col(&two, "y")),
            ("v".into(), col(&two, "u")),
        ],
    )
    .unwrap();
    (both, one)
}

fn options(n: usize) -> FitOptions<Slope> {
    let mut options = FitOptions::<Slope>::new(n);
    options.recipe.preprocess.filter = None;
    options.recipe.settings.max_centres = 6;
    options
}

#[test]
fn each_channel_reads_its_own_signals_by_default() {
    let (both, one) = record(2000);
    let (model, _) =
        sysid::fit_records(&TwoLines, &[("r".into(), &both)], &options(2), &|_| {}).unwrap();
    let w = &model.preprocess().window;
    assert_eq!(
        (w.signals_of(0), w.signals_of(1)),
        (&["u".to_string()][..], &["v".to_string()][..])
    );
    // One choice per channel's candidates, each naming its channel.
    let choices = &model.choice().unwrap().window_signals;
    let named: Vec<(Vec<String>, Vec<String>)> = choices
        .iter()
        .map(|c| (c.channels.clone(), c.taken.clone()))
        .collect();
    assert_eq!(
        named,
        [
            (vec!["y".into()], vec!["u".into()]),
            (vec!["y2".into()], vec!["v".into()])
        ]
    );
    // Channel y's network is the one a fit of y alone on u makes: the
    // windows of y2 do not enter it.
    let (alone, _) =
        sysid::fit_records(&Line, &[("r".into(), &one)], &options(1), &|_| {}).unwrap();
    assert_eq!(model.channel(0).rbf(), alone.channel(0).rbf());
    assert_eq!(model.channel(0).scores(), alone.channel(0).scores());
    // The model file holds each channel's list and reads back the same.
    let text = serde_json::to_string(&model.clone().into_parts().preprocess).unwrap();
    assert!(text.contains(r#""channels":[["u"],["v"]]"#), "{text}");
    // A record prepared for the model: each channel's windows its own.
    let again = model.prepare(&both).unwrap();
    assert_ne!(again.windows(0).row(0), again.windows(1).row(0));
    let predicted = model.predict(&again).unwrap();
    let prepared_alone = alone.prepare(&one).unwrap();
    assert_eq!(predicted[0], alone.predict(&prepared_alone).unwrap()[0]);
    // A file whose window names another number of channels' lists is refused.
    let mut parts = model.into_parts();
    parts.preprocess.window = WindowSpec::per_channel(
        vec![vec!["u".into()], vec!["v".into()], vec!["u".into()]],
        &[],
        50,
    )
    .unwrap();
    let e = sysid::Model::from_parts(parts).unwrap_err();
    assert!(
        e.contains("the signals of 3 channels, not of each of the model's 2"),
        "{e}"
    );
}

#[test]
fn a_named_window_is_every_channels() {
    let (both, _) = record(2000);
    let mut options = options(2);
    options.recipe.preprocess.window = WindowSpec::new(vec!["v".into()], 50).unwrap();
    let (model, _) =
        sysid::fit_records(&TwoLines, &[("r".into(), &both)], &options, &|_| {}).unwrap();
    let w = &model.preprocess().window;
    assert!(!w.is_per_channel());
    assert_eq!(
        (w.signals_of(0), w.signals_of(1)),
        (&["v".to_string()][..], &["v".to_string()][..])
    );
    assert!(model.choice().is_none_or(|c| c.window_signals.is_empty()));
    let text = serde_json::to_string(&model.into_parts().preprocess.window).unwrap();
    assert_eq!(text, r#"{"signals":["v"],"length":50}"#);
}

/// A window of one list for every channel, as every file before per-channel
/// windows holds it, reads as that list for each channel; a file's
/// per-channel lists read back as written.
#[test]
fn window_files_read_as_written() {
    let old: WindowSpec = serde_json::from_str(r#"{"signals":["ax","az"],"length":50}"#).unwrap();
    assert_eq!(
        old,
        WindowSpec::new(vec!["ax".into(), "az".into()], 50).unwrap()
    );
    assert_eq!(old.signals_of(7), ["ax", "az"]);
    let own = WindowSpec::per_channel(vec![vec!["ax".into()], vec!["bx".into()]], &[], 20).unwrap();
    let text = serde_json::to_string(&own).unwrap();
    assert_eq!(
        text,
        r#"{"signals":["ax","bx"],"length":20,"channels":[["ax"],["bx"]]}"#
    );
    assert_eq!(serde_json::from_str::<WindowSpec>(&text).unwrap(), own);
}

/// [`Line`] with no channel: no output to model.
#[derive(Debug, Clone, Copy)]
struct NoChannel;

impl Sensor for NoChannel {
    type Channel = String;
    type Effect = Slope;
    type Axis = String;

    fn channels(&self) -> Vec<String> {
        Vec::new()
    }
    fn wording(&self) -> Wording {
        Line.wording()
    }
    fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError> {
        Ok(raw.clone())
    }
    fn targets(&self, _: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
        Ok(Vec::new())
    }
    fn operating_signals(&self) -> Vec<String> {
        vec!["u".into()]
    }
    fn operating_scale(&self) -> f64 {
        Line.operating_scale()
    }
    fn extra_columns(&self, _: &Signals) -> Vec<String> {
        Vec::new()
    }
    fn candidates(&self, _: &Signals, _: &[usize], _: usize) -> Vec<Candidacy<Slope>> {
        Vec::new()
    }
    fn parse_effect(&self, _: usize, id: &str) -> Result<Slope, SensorError> {
        Line.parse_effect(0, id)
    }
    fn regressors(&self, _: &Signals, _: usize, _: &[Slope]) -> Result<Vec<Vec<f64>>, SensorError> {
        Ok(Vec::new())
    }
    fn separation(&self, k: usize, g: &[Slope], c: &[f64], o: &OperatingStats) -> Separation {
        Line.separation(k, g, c, o)
    }
}

/// A sensor of no channel is an error of its own, whether the window names
/// its signals or leaves them to the records, never a panic.
#[test]
fn a_sensor_of_no_channel_is_an_error() {
    let (_, one) = record(500);
    for window in [
        WindowSpec::new(vec!["u".into()], 10).unwrap(),
        WindowSpec::auto(10).unwrap(),
    ] {
        let pre = sysid::Preprocess {
            filter: None,
            window,
            ..Default::default()
        };
        let e = sysid::Prepared::new(&NoChannel, &one, &pre).unwrap_err();
        assert!(matches!(e, sysid::SysidError::NoChannels), "{e}");
        let e =
            sysid::Prepared::new_many(&NoChannel, &[("a".into(), &one), ("b".into(), &one)], &pre)
                .unwrap_err();
        assert!(matches!(e, sysid::SysidError::NoChannels), "{e}");
    }
}

/// A window naming each channel's signals for another number of channels
/// than the sensor's (a hand-edited file) is refused when records are
/// prepared with it, not read as the shared list for the channels it
/// leaves out.
#[test]
fn a_window_of_another_number_of_channel_lists_is_refused() {
    let (both, _) = record(500);
    for (n, lists) in [(1, r#"[["v"]]"#), (3, r#"[["u"],["v"],["u"]]"#)] {
        let text = format!(r#"{{"signals":["u","v"],"length":10,"channels":{lists}}}"#);
        let pre = sysid::Preprocess {
            filter: None,
            window: serde_json::from_str(&text).unwrap(),
            ..Default::default()
        };
        let e = sysid::Prepared::new(&TwoLines, &both, &pre).unwrap_err();
        assert!(
            matches!(e, sysid::SysidError::WindowChannels { lists, channels: 2 } if lists == n),
            "{e}"
        );
        let said = format!("of {n} channels, not of each of the sensor's 2");
        assert!(e.to_string().contains(&said), "{e}");
    }
}

/// A choice report's `window_signals` reads as one choice or a list of
/// them; any other shape in a hand-edited file is refused naming the key
/// and both shapes, and an error inside a choice names the key too.
#[test]
fn window_signal_choices_in_a_file_are_one_or_a_list_and_said_so_otherwise() {
    let (both, _) = record(2000);
    let c = sysid::choose_window_signals(&TwoLines, &[("r".into(), &both)]).unwrap();
    let one = serde_json::to_string(&c.choices[0]).unwrap();
    let many = serde_json::to_string(&c.choices).unwrap();
    let report =
        |w: &str| format!(r#"{{"candidates":[],"chosen":0,"adev_runs":0,"window_signals":{w}}}"#);
    let read = |w: &str| serde_json::from_str::<sysid::fit::ChoiceReport>(&report(w));
    assert_eq!(read(&one).unwrap().window_signals, c.choices[..1]);
    assert_eq!(read(&many).unwrap().window_signals, c.choices);
    for wrong in [r#""az""#, "3", "true"] {
        let e = read(wrong).unwrap_err().to_string();
        assert!(
            e.contains("`window_signals` to hold one window-signal choice (an object"),
            "{e}"
        );
        assert!(
            e.contains("or a list of them, one per group of channels"),
            "{e}"
        );
        assert!(e.contains("line 1 column"), "{e}");
    }
    let no_rule = one.replace(r#","rule":"#, r#","rules":"#);
    for w in [no_rule.clone(), format!("[{no_rule}]")] {
        let e = read(&w).unwrap_err().to_string();
        assert!(e.contains("window_signals: missing field `rule`"), "{e}");
    }
}

/// A channel whose own signal is constant in every record (a still IMU, a
/// dead accelerometer triad) chooses among every channel's signals, said
/// in its choice, and the other channel's choice stands: the fit does not
/// fail.
#[test]
fn a_channel_whose_own_signals_are_constant_chooses_among_every_channels() {
    let (both, _) = record(2000);
    let still = held(&both, "v", 0.25);
    let c = sysid::choose_window_signals(&TwoLines, &[("r".into(), &still)]).unwrap();
    assert_eq!(c.signals, [["u"], ["u"]]);
    assert_eq!(c.constant, [1]);
    let fell_back = &c.choices[1];
    assert_eq!(fell_back.channels, ["y2"]);
    let measured: Vec<&str> = fell_back
        .signals
        .iter()
        .map(|s| s.signal.as_str())
        .collect();
    assert_eq!(measured, ["u", "v"]);
    let why = fell_back.fallback.as_deref().unwrap();
    assert!(
        why.starts_with("their own v constant in every record: chosen among every candidate"),
        "{why}"
    );
    assert!(c.choices[0].fallback.is_none());
    // Every signal constant: still refused, naming them all.
    let dead = held(&still, "u", 1.0);
    let e = sysid::choose_window_signals(&TwoLines, &[("r".into(), &dead)]).unwrap_err();
    assert!(e.to_string().contains("none of u, v varies"), "{e}");
}

/// `record` with its column `name` held at `value`.
fn held(record: &Signals, name: &str, value: f64) -> Signals {
    let columns = record
        .columns()
        .iter()
        .map(|(n, v)| match n == name {
            true => (n.clone(), vec![value; v.len()]),
            false => (n.clone(), v.clone()),
        })
        .collect();
    Signals::new(record.t().to_vec(), columns).unwrap()
}
