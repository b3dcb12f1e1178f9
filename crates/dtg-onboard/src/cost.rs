//! What one step costs, counted from the tables: floating-point operations
//! (a multiply-add is two; `/` and |x| count one each) and exponentials,
//! so that a measured step can be set against the machine's peak.

use crate::lanes::lane_blocks;
use crate::layout::{LANES, input, kind};
use crate::model::Model;

impl Model<'_> {
    /// Floating-point operations of one step besides the exponentials
    /// ([`Model::exps_per_step`]): the kernel sums, filters and effects
    /// counted from the tables, the calibration's Newton steps estimated
    /// (one step each, the triad's four). A channel sharing another's
    /// centres costs two per centre (its weight's multiply-add).
    pub fn flops_per_step(&self) -> usize {
        let (nc, na) = (self.n_channels, self.n_accels);
        // The covariance's factors: 4 × 3 sums of 7 multiply-adds.
        let mut f = self.calibration_flops() + 4 * 3 * 7 * 2;
        for (c, ch) in self.channels[..nc].iter().enumerate() {
            for e in 0..ch.n_effects {
                f += match self.effect(c, e).0 {
                    kind::COLUMN => 0,
                    kind::LINEAR_G => 5,
                    kind::QUADRATIC_G => 55,
                    _ => 4 * nc + 1,
                } + 9 * self.n_sections
                    + 2;
            }
            let live = lane_blocks(ch.n_centres) * LANES;
            if self.leader[c] == c {
                f += if self.input == input::STATISTICS {
                    // x′ and ‖x′‖², then per centre V + W·q and D multiply-adds.
                    3 * ch.dim + live * (2 + 2 * ch.dim)
                } else {
                    // Per centre the window's distance and the width.
                    live * (3 * ch.dim + 1)
                };
            }
            // The weighted terms, the lanes' pairwise sum, the output.
            f += 2 * live + (LANES - 1) + 3;
        }
        if self.fade.is_some() {
            // Per accelerometer: mean and level over the window, the
            // excesses; the smoothstep, the smoother, one hold per channel.
            f += na * (4 * self.window_len + 12) + 20 + nc * 5;
        }
        f += nc * 9 * self.n_smooth_sections;
        let per_signal = 9 * self.n_in_sections
            + 6
            + if self.input == input::STATISTICS {
                8
            } else {
                0
            };
        f + per_signal * self.n_signals
    }

    /// The ground calibration's share of [`Model::flops_per_step`].
    fn calibration_flops(&self) -> usize {
        if !self.calibrated {
            return 0;
        }
        let (n, na) = (self.n_channels, self.n_accels);
        let mut f = 0;
        if self.force_op.is_some() {
            f += 3 * 2 * na;
        }
        if self.accel_triad {
            // 3 sweeps × 3 axes × 4 Newton steps of ~25 flops.
            f += 3 * 3 * 4 * 25 + 3;
        }
        // Once: the force and the covariance's four factors along each
        // gyro's three axes (75), the g terms (6), the g² terms (66); per pass:
        // the least-squares rate, each gyro's two rates (10), a0 and b (8),
        // the division (2) and one Newton check (9).
        f + n * 147 + 2 * (6 * n + n * 29)
    }

    /// Exponentials of one step: one per lane of each centre set's blocks
    /// ([`crate::LANES`] centres each; the lanes past a set's last centre
    /// are taken with the block).
    pub fn exps_per_step(&self) -> usize {
        (0..self.n_channels)
            .filter(|&c| self.leader[c] == c)
            .map(|c| lane_blocks(self.channels[c].n_centres) * LANES)
            .sum()
    }
}
