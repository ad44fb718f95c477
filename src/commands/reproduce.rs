//! `friction-lab reproduce --out DIR`: the paper reproduced into one folder
//! ([`friction_lab::reproduce::ReproduceRequest`]): Figures 2–7 with notes, the experiment,
//! Table 2, the solver studies, the chain's and the belt's stick–slip map, and a report that
//! links them.

use super::Writing;
use friction_lab::error::AppError;
use friction_lab::reproduce::ReproduceRequest;
use std::time::Instant;

/// Runs `reproduce`: its files written, then the failure of a part that did not finish.
/// `delivery`: the figures' size and resolution, `--replace`, and the command line.
pub fn run(args: &Writing<ReproduceRequest>, delivery: crate::Delivery) -> Result<(), AppError> {
    let start = Instant::now();
    let threads = args.request.threads()?;
    let made = args.request.run(&args.out)?;
    let written = delivery.write(made.files, &args.out, threads)?;
    println!(
        "{} in {:.2} s",
        written.line(),
        start.elapsed().as_secs_f64()
    );
    if let Some(note) = written.stop_note() {
        crate::print_note(&note);
    }
    made.failure.map_or(Ok(()), Err)
}
