//! `friction-lab phenomena --out DIR`: Table 2 decided by simulation for the paper's six
//! models and the reference models, beside the paper's claims, with the numbers that
//! decided each cell.

use super::Writing;
use friction_lab::error::AppError;
use friction_lab::ranges;
use friction_lab::study::PhenomenaRequest;
use std::time::Instant;

/// Runs `phenomena`: its files written, then the advice and the failure of undecided cells.
/// `delivery`: the figures' size and resolution, and `--replace`.
pub fn run(args: &Writing<PhenomenaRequest>, delivery: crate::Delivery) -> Result<(), AppError> {
    let start = Instant::now();
    let threads = ranges::threads(args.request.threads)?;
    let made = args.request.run(&args.out)?;
    let written = delivery.write(made.files, &args.out, threads)?;
    println!(
        "{} in {:.1} s",
        written.line(),
        start.elapsed().as_secs_f64()
    );
    for warning in made.warnings.iter().chain(written.stop_note().iter()) {
        crate::print_note(warning);
    }
    made.failure.map_or(Ok(()), Err)
}
