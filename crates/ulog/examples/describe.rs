//! Lists what a ULog file has: `cargo run -p ulog --example describe -- FLIGHT.ulg`
//! prints its header, what the reader skipped, and one line per topic
//! instance (samples, mean rate, fields), the names a unit file's `[ulog]`
//! table uses.

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: describe FLIGHT.ulg");
        std::process::exit(2);
    };
    match ulog::Ulog::read(&path) {
        Ok(log) => {
            let h = log.header();
            println!(
                "{path}: ULog version {}, {} appended section(s); {}",
                h.version,
                log.integrity().appended_sections,
                log.integrity().summary()
            );
            print!("{}", log.describe());
        }
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}
