//! Where the test stands: latitude and the cluster's orientation, giving the
//! Earth rate and gravity in the cluster frame.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Earth's sidereal rotation rate, deg/h (7.2921159e-5 rad/s).
///
/// ```
/// assert!((nav_sensors::sim::EARTH_RATE_DEG_H - 7.2921159e-5f64.to_degrees() * 3600.0).abs() < 1e-5);
/// ```
pub const EARTH_RATE_DEG_H: f64 = 15.041_067;

/// A local direction (east-north-up frame).
///
/// ```
/// let d: nav_sensors::sim::Direction = toml::from_str::<toml::Table>("d = \"east\"").unwrap()["d"]
///     .clone().try_into().unwrap();
/// assert_eq!(d, nav_sensors::sim::Direction::East);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    North,
    South,
    East,
    West,
    Up,
    Down,
}

impl Direction {
    /// The unit vector in the local east-north-up frame.
    ///
    /// ```
    /// use nav_sensors::sim::Direction;
    /// assert_eq!(Direction::Up.enu(), nalgebra::Vector3::new(0.0, 0.0, 1.0));
    /// ```
    pub fn enu(self) -> Vector3<f64> {
        match self {
            Direction::East => Vector3::new(1.0, 0.0, 0.0),
            Direction::West => Vector3::new(-1.0, 0.0, 0.0),
            Direction::North => Vector3::new(0.0, 1.0, 0.0),
            Direction::South => Vector3::new(0.0, -1.0, 0.0),
            Direction::Up => Vector3::new(0.0, 0.0, 1.0),
            Direction::Down => Vector3::new(0.0, 0.0, -1.0),
        }
    }
}

/// Where the cluster's x and z axes point; y completes a right-handed frame
/// (y = z × x).
///
/// ```
/// use nav_sensors::sim::{Direction, Orientation};
/// let o = Orientation::default(); // x north, z up: y points west
/// assert_eq!(o.axes_enu().unwrap()[1], Direction::West.enu());
/// assert!(Orientation { x: Direction::Up, z: Direction::Down }.axes_enu().is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Orientation {
    /// Direction of cluster x.
    pub x: Direction,
    /// Direction of cluster z.
    pub z: Direction,
}

impl Default for Orientation {
    /// Cluster z up, x north (so the stationary unit reads +1 g on z).
    fn default() -> Self {
        Self {
            x: Direction::North,
            z: Direction::Up,
        }
    }
}

impl Orientation {
    /// The cluster axes x, y, z as east-north-up vectors, or `None` when x
    /// and z are not perpendicular.
    ///
    /// ```
    /// use nav_sensors::sim::{Direction, Orientation};
    /// let [x, y, z] = Orientation { x: Direction::East, z: Direction::Up }.axes_enu().unwrap();
    /// assert_eq!(y, Direction::North.enu());
    /// assert_eq!(x.cross(&y), z);
    /// ```
    pub fn axes_enu(&self) -> Option<[Vector3<f64>; 3]> {
        let x = self.x.enu();
        let z = self.z.enu();
        (x.dot(&z) == 0.0).then(|| [x, z.cross(&x), z])
    }
}

/// The test site.
///
/// ```
/// use nav_sensors::sim::{Site, EARTH_RATE_DEG_H};
/// let s = Site { latitude_deg: 30.0, ..Site::default() };
/// let w = s.earth_rate_cluster_deg_h().unwrap();
/// // x north, z up: (Ω cos φ, 0, Ω sin φ).
/// assert!((w.x - EARTH_RATE_DEG_H * 30f64.to_radians().cos()).abs() < 1e-12);
/// assert!((w.z - EARTH_RATE_DEG_H * 0.5).abs() < 1e-12);
/// assert_eq!(s.gravity_cluster_g().unwrap(), nalgebra::Vector3::new(0.0, 0.0, 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Site {
    /// Geodetic latitude, degrees north.
    pub latitude_deg: f64,
    /// Cluster orientation.
    #[serde(default)]
    pub orientation: Orientation,
}

impl Default for Site {
    /// 8.5° N (Thiruvananthapuram, where the paper's sensor unit was tested), z up, x north.
    fn default() -> Self {
        Self {
            latitude_deg: 8.5,
            orientation: Orientation::default(),
        }
    }
}

impl Site {
    /// Earth rate resolved into the cluster frame, deg/h (`None` for an invalid orientation).
    ///
    /// ```
    /// use nav_sensors::sim::{Direction, Orientation, Site};
    /// let s = Site { latitude_deg: 90.0, orientation: Orientation { x: Direction::North, z: Direction::Down } };
    /// assert!((s.earth_rate_cluster_deg_h().unwrap().z + 15.041067).abs() < 1e-9);
    /// ```
    pub fn earth_rate_cluster_deg_h(&self) -> Option<Vector3<f64>> {
        let lat = self.latitude_deg.to_radians();
        let w = Vector3::new(0.0, lat.cos(), lat.sin()) * EARTH_RATE_DEG_H;
        self.resolve(&w)
    }

    /// The stationary unit's specific force in the cluster frame, g: the
    /// reaction to gravity, +1 g up. (The record's g is local gravity.)
    ///
    /// ```
    /// use nav_sensors::sim::{Direction, Orientation, Site};
    /// let s = Site { orientation: Orientation { x: Direction::Up, z: Direction::East }, ..Site::default() };
    /// assert_eq!(s.gravity_cluster_g().unwrap(), nalgebra::Vector3::new(1.0, 0.0, 0.0));
    /// ```
    pub fn gravity_cluster_g(&self) -> Option<Vector3<f64>> {
        self.resolve(&Vector3::new(0.0, 0.0, 1.0))
    }

    fn resolve(&self, v_enu: &Vector3<f64>) -> Option<Vector3<f64>> {
        let a = self.orientation.axes_enu()?;
        Some(Vector3::new(
            a[0].dot(v_enu),
            a[1].dot(v_enu),
            a[2].dot(v_enu),
        ))
    }
}
