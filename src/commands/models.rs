//! `friction-lab models [--json]`: every model with its equation and parameters, and the
//! parameters with units, defaults, ranges and named sets ([`friction_lab::listing`]).

use friction_lab::error::AppError;
use friction_lab::listing;

/// Prints the listing, as text or as JSON.
pub fn run(json: bool) -> Result<(), AppError> {
    if json {
        println!("{}", listing::json());
    } else {
        print!("{}", listing::text());
    }
    Ok(())
}
