//! The glitch screen on the real three-IMU quadrotor flights
//! (`data/realdata/multi-imu/`, `units/multi-imu.toml`): IMU 2's g2x
//! strays from the other IMUs at rows 4683–4684 and 4701–4702 of
//! `qdr_horizontal_path11.csv` (a dropout resampled into the log: it ramps
//! toward zero and back), and nowhere else on either flight; no clean
//! sample of either flight reaches 8 robust σ.

use nav_sensors::record::{GLITCH_Z, Record, glitch_scores, glitches};
use nav_sensors::unit::Unit;

fn flight(file: &str) -> (Unit, Record) {
    let root = format!("{}/../..", env!("CARGO_MANIFEST_DIR"));
    let unit = Unit::load(format!("{root}/units/multi-imu.toml")).unwrap();
    let mut read =
        Record::read_with_unit(format!("{root}/data/realdata/multi-imu/{file}"), &unit).unwrap();
    assert_eq!(read.records.len(), 1);
    (unit, read.records.remove(0))
}

#[test]
fn path11s_glitches_are_imu_2s_four_rows_and_path1_has_none() {
    let (unit, rec) = flight("qdr_horizontal_path11.csv");
    let g = glitches(&unit, &rec);
    let found: Vec<(&str, std::ops::Range<usize>)> = g
        .iter()
        .map(|g| (g.column.as_str(), g.rows.clone()))
        .collect();
    assert_eq!(found, [("g2x", 4683..4685), ("g2x", 4701..4703)], "{g:?}");
    assert!(
        g.iter().all(|g| g.peak_z > GLITCH_Z && g.peak_z < 30.0),
        "{g:?}"
    );
    assert_eq!(
        g[0].to_string(),
        "g2x rows 4683–4684 (t 39.023–39.032 s, 22.1 σ)"
    );
    let (unit, rec) = flight("qdr_vertical_path1.csv");
    assert!(glitches(&unit, &rec).is_empty());
}

/// Each piece of 1000 rows of either flight, scored on its own median
/// and spread, gives no glitch but path_11's two.
#[test]
fn pieces_of_the_clean_flights_give_no_glitch() {
    for file in ["qdr_horizontal_path11.csv", "qdr_vertical_path1.csv"] {
        let (unit, rec) = flight(file);
        let mut start = 0;
        while start + 1000 <= rec.len() {
            let piece = rec.slice(start..start + 1000);
            let g = glitches(&unit, &piece);
            let clean = g.iter().all(|g| {
                file.contains("path11") && (4683 - start..4703 - start).contains(&g.rows.start)
            });
            assert!(clean, "{file} from {start}: {g:?}");
            start += 1000;
        }
    }
}

/// The module's false-alarm statement: outside path_11's glitches and
/// their neighbours (rows 4680–4705), no sample of either flight reaches
/// 8 robust σ on any gyro, a margin of 2 σ below [`GLITCH_Z`].
#[test]
fn no_clean_sample_of_either_flight_reaches_8_sigma() {
    for file in ["qdr_horizontal_path11.csv", "qdr_vertical_path1.csv"] {
        let (unit, rec) = flight(file);
        let mut highest = (0.0_f64, String::new(), 0);
        for (k, z) in glitch_scores(&unit, &rec).iter().enumerate() {
            for (i, &v) in z.iter().enumerate() {
                let glitch = file.contains("path11") && (4680..4705).contains(&i);
                if !glitch && v > highest.0 {
                    highest = (v, unit.gyros()[k].name.clone(), i);
                }
            }
        }
        eprintln!(
            "{file}: highest clean score {:.2} σ ({} row {})",
            highest.0, highest.1, highest.2
        );
        assert!(highest.0 < 8.0, "{file}: {highest:?}");
        assert!(
            highest.0 > 3.0,
            "{file}: a score that never leaves 3 σ is not a score: {highest:?}"
        );
    }
}

/// A four-gyro unit (tetra) has one residue: a glitch on any gyro moves it
/// alike, so the screen detects it and names every gyro, not one picked by
/// rounding (the rule of `nav_sensors::fdi`: four gyros detect but cannot
/// isolate).
#[test]
fn a_glitch_a_four_gyro_unit_cannot_isolate_names_every_gyro() {
    let unit = Unit::builtin("tetra").unwrap();
    let mut csv = format!("t,{},ax,ay,az\n", unit.gyro_names().join(","));
    for i in 0..100 {
        let g: Vec<String> = (0..4)
            .map(|k| {
                let ripple = if (i + k) % 2 == 0 { 0.01 } else { -0.01 };
                ripple + if i == 50 && k == 1 { 5.0 } else { 0.0 }
            })
            .map(|v: f64| v.to_string())
            .collect();
        csv += &format!("{},{},0,0,1\n", i as f64 * 0.01, g.join(","));
    }
    let rec = &Record::from_reader_with_unit(csv.as_bytes(), "tetra.csv", &unit)
        .unwrap()
        .records[0];
    let g = glitches(&unit, rec);
    assert_eq!(g.len(), 1, "{g:?}");
    assert_eq!(g[0].rows, 50..51);
    assert_eq!(g[0].candidates, ["g1", "g2", "g3", "g4"], "{g:?}");
    assert!(
        g[0].to_string()
            .starts_with("one of g1, g2, g3, g4 (the unit cannot tell which) row 50"),
        "{}",
        g[0]
    );
}
