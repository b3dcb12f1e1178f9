//! The networks' kernel sums of one step, in vector lanes: per centre set,
//! blocks of [`LANES`] centres whose arguments −‖x − cᵢ‖²/βᵢ² are summed
//! side by side (for the statistics input by the expansion about the set's
//! mean, [`crate::lanes`]; for the raw window as each window's distance to
//! the tables' centres), whose exponentials are taken in one branch-free
//! loop over a chunk of blocks' lanes, and whose terms each sharing channel
//! weights into one partial sum per lane; the lanes are added pairwise at
//! the end. The exported C takes the same blocks in the same order.

use crate::lanes::lane_blocks;
use crate::layout::{LANES, MAX_CHANNELS, MAX_SIGNALS, input};
use crate::maths::{lane_sum, sq_dist};
use crate::model::Model;
use fastexp::exp_neg11;

/// Blocks whose exponentials are taken in one loop: a loop of a run-time
/// length up to this many blocks' lanes, which the compiler vectorises
/// lane by lane (a loop of one block's [`LANES`] it unrolls into scalar
/// code; over 16 blocks it vectorised the arguments across blocks, with
/// gathers). K = 100 centres are two chunks.
const CHUNK: usize = 8;

/// A chunk's arguments and exponentials, kept across sets and chunks (set
/// once a step: a chunk reads only the lanes it wrote).
struct Scratch {
    arg: [f64; CHUNK * LANES],
    phi: [f64; CHUNK * LANES],
}

/// Every channel's kernel terms added to its `ys` and `nets` (the input:
/// the statistics in `st`, or the windows of the rings whose oldest sample
/// is at `ring_pos`). Channels that share a centre set take each kernel
/// value computed once, times their own weight.
#[inline(always)]
pub(crate) fn network_terms(
    m: &Model,
    st: &[f64],
    ring_pos: usize,
    ys: &mut [f64; MAX_CHANNELS],
    nets: &mut [f64; MAX_CHANNELS],
) {
    // One partial sum per lane and channel (each channel is in one set).
    let mut acc = [[0.0; LANES]; MAX_CHANNELS];
    let mut scratch = Scratch {
        arg: [0.0; CHUNK * LANES],
        phi: [0.0; CHUNK * LANES],
    };
    for c in 0..m.n_channels {
        if m.leader[c] != c {
            continue;
        }
        let members = &m.members[c][..m.n_members[c]];
        let set = (m, c, st, members);
        if m.input == input::STATISTICS {
            statistics_terms(set, &mut scratch, &mut acc);
        } else {
            let w = &st[m.channels[c].lanes..][..m.kernel_lanes_len(c)];
            set_blocks(set, &mut scratch, &mut acc, |b0, arg| {
                for (b, a) in arg.iter_mut().enumerate() {
                    window_args(m, c, st, ring_pos, (w, b0 + b), a);
                }
            });
        }
        for &j in members {
            let sum = lane_sum(&acc[j as usize]);
            ys[j as usize] += sum;
            nets[j as usize] += sum;
        }
    }
}

/// A centre set: the model, its leader, the state, its members.
type Set<'a, 'm> = (&'a Model<'m>, usize, &'a [f64], &'a [u8]);

/// Set `c`'s blocks of [`LANES`] centres, [`CHUNK`] at a time: `args`
/// writes the arguments of the chunk's blocks from block b₀ on, their exponentials are taken in one
/// branch-free loop over the chunk, and each member's weights take the
/// terms into its partial sums `acc`.
#[inline(always)]
fn set_blocks(
    (m, c, st, members): Set,
    s: &mut Scratch,
    acc: &mut [[f64; LANES]; MAX_CHANNELS],
    mut args: impl FnMut(usize, &mut [[f64; LANES]]),
) {
    let blocks = lane_blocks(m.channels[c].n_centres);
    let mut b0 = 0;
    while b0 < blocks {
        let nb = CHUNK.min(blocks - b0);
        args(b0, s.arg[..nb * LANES].as_chunks_mut::<LANES>().0);
        for (p, a) in s.phi[..nb * LANES].iter_mut().zip(&s.arg) {
            *p = exp_neg11(*a);
        }
        for &j in members {
            let j = j as usize;
            let w = &st[m.channels[j].weight_lanes + b0 * LANES..][..nb * LANES];
            for (p, w) in s.phi.chunks_exact(LANES).zip(w.chunks_exact(LANES)) {
                for ((a, p), w) in acc[j].iter_mut().zip(p).zip(w) {
                    *a += p * w;
                }
            }
        }
        b0 += nb;
    }
}

/// Set `c`'s terms on the statistics input: its statistics centred on the
/// set's mean, their squared norm, its blocks' arguments V + W·q + Σⱼ x′ⱼUⱼ
/// summed in input order. The dimensions of one, two and three signals are
/// laid out at compile time, so that the sum over the inputs is unrolled
/// with a block's lanes in registers.
#[inline(always)]
fn statistics_terms(set: Set, s: &mut Scratch, acc: &mut [[f64; LANES]; MAX_CHANNELS]) {
    let (m, c, st, _) = set;
    let ch = &m.channels[c];
    let lanes = &st[ch.lanes..ch.lanes + m.kernel_lanes_len(c)];
    match ch.dim {
        3 => statistics_terms_of::<3>(set, s, acc, lanes),
        6 => statistics_terms_of::<6>(set, s, acc, lanes),
        9 => statistics_terms_of::<9>(set, s, acc, lanes),
        dim => {
            let mut xm = [0.0; 3 * MAX_SIGNALS];
            let q = centred_statistics(m, c, st, lanes, &mut xm[..dim]);
            let stride = (dim + 2) * LANES;
            set_blocks(set, s, acc, |b0, arg| {
                let blocks = lanes[dim + b0 * stride..].chunks_exact(stride);
                for (a, block) in arg.iter_mut().zip(blocks) {
                    block_args(block.as_chunks::<LANES>().0, (&xm[..dim], q), a);
                }
            });
        }
    }
}

/// [`statistics_terms`] of dimension `D` (`lanes`: the set's).
#[inline(always)]
fn statistics_terms_of<const D: usize>(
    set: Set,
    s: &mut Scratch,
    acc: &mut [[f64; LANES]; MAX_CHANNELS],
    lanes: &[f64],
) {
    let (m, c, st, _) = set;
    let stride = (D + 2) * LANES;
    let mut x = [0.0; D];
    let q = centred_statistics(m, c, st, lanes, &mut x);
    set_blocks(set, s, acc, |b0, arg| {
        let blocks = lanes[D + b0 * stride..].chunks_exact(stride);
        for (a, block) in arg.iter_mut().zip(blocks) {
            block_args(block.as_chunks::<LANES>().0, (&x, q), a);
        }
    });
}

/// Set `c`'s statistics input centred on the set's mean into `xm` (its
/// dimension long; x′ = x − m; x: the statistics of the set's signals, in
/// order); returns ‖x′‖².
#[inline(always)]
fn centred_statistics(m: &Model, c: usize, st: &[f64], lanes: &[f64], xm: &mut [f64]) -> f64 {
    let ch = &m.channels[c];
    let mut j = 0;
    for s in 0..m.n_signals {
        if ch.mask & (1 << s) != 0 {
            for t in 0..3 {
                xm[j] = st[m.st.features + 3 * s + t] - lanes[j];
                j += 1;
            }
        }
    }
    let mut q = 0.0;
    for x in xm.iter() {
        q += x * x;
    }
    q
}

/// V + W·q + Σⱼ xⱼUⱼ of one block's `rows` (U's, then V, then W).
#[inline(always)]
fn block_args(rows: &[[f64; LANES]], (x, q): (&[f64], f64), arg: &mut [f64; LANES]) {
    let (u, vw) = rows.split_at(x.len());
    let (v, w) = (&vw[0], &vw[1]);
    for i in 0..LANES {
        arg[i] = v[i] + w[i] * q;
    }
    for (x, uj) in x.iter().zip(u) {
        for i in 0..LANES {
            arg[i] += x * uj[i];
        }
    }
}

/// The arguments of block `b` of set `c` on the raw window (`lanes`: the
/// set's −1/β²): each centre's squared distance to the windows of its
/// signals (oldest sample at `ring_pos`), times −1/β²; 0 past the last
/// centre.
#[inline(always)]
fn window_args(
    m: &Model,
    c: usize,
    st: &[f64],
    ring_pos: usize,
    (w, b): (&[f64], usize),
    arg: &mut [f64; LANES],
) {
    let ch = &m.channels[c];
    let (l, dim, n) = (m.window_len, ch.dim, ch.n_centres);
    for (i, a) in arg.iter_mut().enumerate().take(n - b * LANES) {
        let k = b * LANES + i;
        let mut at = ch.centres + 8 * dim * k;
        let mut r2 = 0.0;
        for s in 0..m.n_signals {
            if ch.mask & (1 << s) != 0 {
                let win = &st[m.st.rings + 2 * l * s + ring_pos..][..l];
                r2 += sq_dist(&m.bytes[at..at + 8 * l], win);
                at += 8 * l;
            }
        }
        *a = r2 * w[k];
    }
}
