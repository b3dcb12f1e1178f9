//! Prints a built-in scenario as TOML, a starting point for your own:
//!
//! ```sh
//! cargo run --release -p nav-sensors --example scenario_toml -- triaxial_hidden > my_test.toml
//! ```

use nav_sensors::sim::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let name = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "paper_z_random".into());
    let scenario = Scenario::builtin(&name).ok_or_else(|| {
        format!(
            "unknown built-in scenario '{name}' (valid: {})",
            Scenario::BUILTIN.join(", ")
        )
    })?;
    print!("{}", scenario.to_toml()?);
    Ok(())
}
