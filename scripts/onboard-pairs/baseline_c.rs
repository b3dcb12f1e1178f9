//! The C of onboard tables of layout 2 (the paper's six channels) or 3
//! (any unit) as 5b6a72d's exporter wrote it: scripts/onboard-pairs.sh
//! copies this file into the baseline's checkout as an example of its
//! dtg-vib and runs it there.
//!
//!     baseline_c TABLES OUT_DIR [UNIT_FILE]

use dtg_vib::export::{Precision, Tables, c_sources_from_tables, unit_c_sources};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let t = Tables {
        bytes: std::fs::read(&args[1]).expect("the tables"),
        extra: vec![],
    };
    let c = match args.get(3) {
        None => c_sources_from_tables(&t, Precision::F64),
        Some(u) => {
            let unit = nav_sensors::unit::Unit::resolve(u).expect("the unit file");
            unit_c_sources(&t, &unit, Precision::F64)
        }
    }
    .expect("C of the tables");
    std::fs::create_dir_all(&args[2]).expect("the output folder");
    for (name, text) in c.files() {
        std::fs::write(std::path::Path::new(&args[2]).join(name), text).expect("writable");
    }
}
