//! The command-line flags. Names are a contract with scripts and the docs: keep them.
//! `--centres` and `--max-centres` are spelt as the code spells centre; `--centers` and
//! `--max-centers`, the spelling of earlier releases, stay as visible aliases.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use rbf::{KMeansAlgorithm, KMeansInit, Kernel, PolyTail};
use rbf_cli::settings::{
    Centres, CvScheme, FitSettings, StopArg, WidthArg, parse_count, parse_ridge, parse_tol,
};

/// Radial-basis-function networks on CSV data: fit, predict, cross-validate.
#[derive(Debug, Parser)]
#[command(name = "rbf", version, about, long_about = None, max_term_width = 100)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Threads for the numerical kernels, 1 to 256 (1: sequential) [default: every core].
    #[arg(long, global = true, value_name = "N", value_parser = parse_threads, allow_hyphen_values = true)]
    pub threads: Option<usize>,
}

/// The most threads `--threads` takes: far above any core count this tool
/// meets, far below what makes spawning the pool itself the work (10,000
/// threads took minutes to start).
pub const MAX_THREADS: usize = 256;

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            Err(format!(
                "must be a whole number from 1 to {MAX_THREADS} (this machine has {cores} cores)"
            ))
        }
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Fit a network on the training rows, score it on the validation rows, save it.
    ///
    /// Rows: with --split-column, rows marked `train` train and rows marked `val`
    /// validate (any other value is an error). Without it, the seed paper's interleaved
    /// split: data rows 0, 2, 4, … (the 1st, 3rd, 5th … after the header) train and rows 1, 3, 5, …
    /// validate.
    Fit(FitArgs),
    /// Predict every row of a CSV file with a saved model.
    ///
    /// The model's input columns are found by name; the output CSV has a `prediction`
    /// column, and the target and `residual` (target − prediction) when the file has the
    /// target column.
    Predict(PredictArgs),
    /// Cross-validate and grid-search width × size × ridge (the library's grid_search).
    ///
    /// With OLS, one forward selection per fold and width gives every size in --sizes or
    /// --tols. Prints per-grid-point mean ± sd validation scores, the best point (lowest
    /// mean validation NMSE) and its per-fold scores.
    Cv(CvArgs),
}

/// Where the data is and which columns to use.
#[derive(Debug, Args)]
pub struct DataArgs {
    /// CSV file with a header row (`#` starts a comment line).
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// The column to predict.
    #[arg(long, value_name = "COL")]
    pub target: String,
    /// Input columns, comma-separated [default: every numeric column but the target
    /// and the split column].
    #[arg(long, value_name = "COL,COL,...", value_delimiter = ',')]
    pub inputs: Option<Vec<String>>,
}

/// The network.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// Centre selection: ols (forward selection by error-reduction ratio over the
    /// training rows), kmeans (k-means++ seeded, QR weights), random (seeded subset, QR
    /// weights), all (every training row; interpolation, or smoothing with --ridge).
    /// [default: ols]
    #[arg(
        long = "centres",
        visible_alias = "centers",
        value_name = "ols|kmeans|random|all",
        default_value = "ols"
    )]
    pub centres: Centres,
    /// Number of centres: the most for ols (fewer if --tol stops it), exactly for kmeans
    /// and random [default: 50].
    #[arg(long = "max-centres", visible_alias = "max-centers", value_name = "K", value_parser = parse_count, allow_hyphen_values = true)]
    pub max_centres: Option<usize>,
    /// kmeans only: whose Lloyd iterations follow the seeded k-means++ start — lloyd
    /// (the library's: distances by faer products, scikit-learn's update and stopping
    /// rule) or linfa (linfa-clustering's KMeans) [default: lloyd].
    #[arg(long, value_name = "lloyd|linfa")]
    pub kmeans_algorithm: Option<KMeansAlgorithm>,
    /// kmeans only: how each start is seeded — greedy (scikit-learn's greedy k-means++,
    /// 2 + ln K draws per centre, the best kept) or plusplus (one draw per centre, as
    /// linfa) [default: greedy].
    #[arg(long, value_name = "greedy|plusplus")]
    pub kmeans_init: Option<KMeansInit>,
    /// kmeans only: seeded starts, the lowest inertia kept (scikit-learn's n_init)
    /// [default: 1].
    #[arg(long, value_name = "N", value_parser = parse_count, allow_hyphen_values = true)]
    pub n_init: Option<usize>,
    /// Polynomial tail: -1 none, 0 constant, 1 linear, 2 quadratic, on the inputs mapped
    /// to the unit box (scipy RBFInterpolator's degree); replaces the bias [default: a
    /// constant on unscaled inputs; with --centres all the kernel's minimum degree].
    #[arg(
        long,
        value_name = "D",
        allow_negative_numbers = true,
        allow_hyphen_values = true
    )]
    pub degree: Option<PolyTail>,
    /// ols only: choose among a seeded random subsample of M training rows instead of
    /// all of them (the way to large files: the candidate matrix is rows × M).
    #[arg(long, value_name = "M", value_parser = parse_count, allow_hyphen_values = true)]
    pub candidates: Option<usize>,
    /// ols only: select centres on a seeded subsample of R training rows, then solve
    /// the weights on every row by a streaming row-block QR (memory independent of the
    /// number of rows) [default: every row up to 20000, else 20000, with --candidates
    /// 2000 unless given].
    #[arg(long, value_name = "R", value_parser = parse_count, allow_hyphen_values = true)]
    pub selection_rows: Option<usize>,
    /// ols only: stream the candidates as an f32 copy with f64 sums, every pick decided
    /// on exact f64 ERRs (f32: half the bytes a pick, the same picks), or as f64
    /// columns [default: f32].
    #[arg(long, value_name = "f32|f64")]
    pub ols_stream: Option<rbf::StreamPrecision>,
    /// ols only: how many centres to keep — press (the least leave-one-out error along
    /// the selection path, from its orthogonal basis at no extra pass), gcv (the least
    /// generalised cross-validation score), err:RHO (as --tol RHO) or k:K (as
    /// --max-centres K). With press or gcv, --max-centres bounds the path [default: a
    /// tenth of the training rows, 10 to 200] [default: run to --max-centres].
    #[arg(long, value_name = "press|gcv|err:RHO|k:K")]
    pub stop: Option<StopArg>,
    /// ols only: stop once 1 − ΣERR < RHO [default: 0, run to --max-centres].
    #[arg(allow_negative_numbers = true, long, value_name = "RHO", value_parser = parse_tol, allow_hyphen_values = true)]
    pub tol: Option<f64>,
    /// Kernel: gaussian exp(−r²/β²), multiquadric, inverse-multiquadric,
    /// inverse-quadratic, thin-plate, cubic, wendland-c2.
    #[arg(long, value_name = "NAME", default_value = "gaussian")]
    pub kernel: Kernel,
    /// Width β in input units, or auto: β = the median pairwise distance between the
    /// candidate centres (training rows for ols and all, the centres for kmeans and
    /// random; a seeded 1000-point subsample above that).
    /// With --stop press|gcv (ols), auto is a search: 0.25, 0.5, 1, 2 and 4 times that
    /// median, the width with the least PRESS wins (JSON: width_search).
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "BETA|auto",
        default_value = "auto",
        allow_hyphen_values = true
    )]
    pub width: WidthArg,
    /// Ridge λ ≥ 0 on the kernel weights (with --centres all: added to the kernel
    /// matrix's diagonal, scipy's `smoothing`).
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "L",
        default_value_t = 0.0,
        value_parser = parse_ridge,
        allow_hyphen_values = true
    )]
    pub ridge: f64,
    /// Standardise every input to zero mean and unit variance (β is then in
    /// standardised units).
    #[arg(long)]
    pub standardize: bool,
    /// Seed of every random draw (k-means, random centres, candidate subsample, k-fold).
    #[arg(
        long,
        value_name = "S",
        default_value_t = 42,
        allow_hyphen_values = true
    )]
    pub seed: u64,
}

impl ModelArgs {
    pub fn settings(&self) -> FitSettings {
        FitSettings {
            centres: self.centres,
            max_centres: self.max_centres,
            candidates: self.candidates,
            selection_rows: self.selection_rows,
            ols_stream: self.ols_stream,
            kmeans_algorithm: self.kmeans_algorithm,
            kmeans_init: self.kmeans_init,
            n_init: self.n_init,
            degree: self.degree,
            tol: self.tol,
            stop: self.stop,
            kernel: self.kernel,
            width: self.width,
            ridge: self.ridge,
            standardize: self.standardize,
            seed: self.seed,
        }
    }
}

#[derive(Debug, Args)]
pub struct FitArgs {
    #[command(flatten)]
    pub data: DataArgs,
    /// Column whose cells say `train` or `val` for each row [default: interleaved split,
    /// even data rows train, odd rows validate].
    #[arg(long, value_name = "COL")]
    pub split_column: Option<String>,
    #[command(flatten)]
    pub model: ModelArgs,
    /// Where to write the model (JSON, with the input and target column names).
    #[arg(long, value_name = "MODEL.json")]
    pub out: PathBuf,
    /// Print one JSON object on stdout (n_train, n_val, dim, n_centers, fit_seconds,
    /// train_rmse, val_rmse, val_nmse, kernel, width, condition, OLS picks, …).
    #[arg(long)]
    pub json: bool,
    /// No progress bar and no summary.
    #[arg(long)]
    pub quiet: bool,
}

#[derive(Debug, Args)]
pub struct PredictArgs {
    /// A model written by `rbf fit --out`.
    #[arg(long, value_name = "MODEL.json")]
    pub model: PathBuf,
    /// CSV file holding (at least) the model's input columns.
    #[arg(long, value_name = "FILE.csv")]
    pub data: PathBuf,
    /// Where to write the predictions (CSV).
    #[arg(long, value_name = "PRED.csv")]
    pub out: PathBuf,
    /// Print one JSON object on stdout (n_rows, predict_seconds, rmse and nmse when the
    /// target column is present).
    #[arg(long)]
    pub json: bool,
    /// No summary.
    #[arg(long)]
    pub quiet: bool,
}

#[derive(Debug, Args)]
pub struct CvArgs {
    #[command(flatten)]
    pub data: DataArgs,
    #[command(flatten)]
    pub model: ModelArgs,
    /// kfold (shuffled, seeded), interleaved (fold f validates every k-th row) or
    /// blocked (contiguous blocks: the honest choice for overlapping windows).
    #[arg(long, value_name = "kfold|interleaved|blocked")]
    pub split: CvScheme,
    /// Number of folds.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 5,
        allow_hyphen_values = true
    )]
    pub folds: usize,
    /// blocked only: rows dropped from training on each side of the validation block
    /// (at least the window length for windowed inputs).
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    pub gap: Option<usize>,
    /// Widths to try (numbers or auto) [default: --width].
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "B1,B2,...",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub widths: Vec<WidthArg>,
    /// Numbers of centres to try [default: --max-centres].
    #[arg(
        long,
        value_name = "K1,K2,...",
        value_delimiter = ',',
        conflicts_with = "tols",
        value_parser = parse_count,
        allow_hyphen_values = true
    )]
    pub sizes: Vec<usize>,
    /// ols only: tolerances ρ to try [default: --tol].
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "R1,R2,...",
        value_delimiter = ',',
        value_parser = parse_tol,
        allow_hyphen_values = true
    )]
    pub tols: Vec<f64>,
    /// Ridges to try [default: --ridge].
    #[arg(
        allow_negative_numbers = true,
        long,
        value_name = "L1,L2,...",
        value_delimiter = ',',
        value_parser = parse_ridge,
        allow_hyphen_values = true
    )]
    pub ridges: Vec<f64>,
    /// Print one JSON object on stdout (every grid point with its folds, and the best).
    #[arg(long)]
    pub json: bool,
    /// No spinner.
    #[arg(long)]
    pub quiet: bool,
}
