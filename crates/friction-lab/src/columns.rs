//! A [`Table`]'s columns as typed vectors: how a front end that is not a file (Python's
//! numpy and pandas) receives the numbers of a CSV file without their text.

use crate::output::{Cell, Table};
use friction_models::params::show;

/// One column of a table as values of one type, as a CSV reader types the file's column
/// (pandas' `read_csv`): [`Column::of`] says which.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// Every cell a whole number, none empty.
    Integers(Vec<i64>),
    /// Every cell a number or empty (NaN).
    Numbers(Vec<f64>),
    /// Every cell `true` or `false`.
    Booleans(Vec<bool>),
    /// Anything else: each cell's text (a number as the file writes it), `None` where empty;
    /// and the columns of a table without rows.
    Texts(Vec<Option<String>>),
}

/// The largest magnitude below which every whole double is an exact `i64`: 2⁵³.
const EXACT_INTEGER: f64 = 9_007_199_254_740_992.0;

impl Column {
    /// Column `k` of `table`: [`Column::Integers`] when every cell is a whole number below
    /// 2⁵³ in magnitude; else [`Column::Numbers`] when every cell is a number or empty (a
    /// column of empty cells is one of NaN); else [`Column::Booleans`] when every cell is `true` or `false`;
    /// else [`Column::Texts`]. An empty table's column is `Texts`, empty.
    pub fn of(table: &Table, k: usize) -> Column {
        let cells: Vec<&Cell> = table.rows.iter().map(|r| &r[k]).collect();
        let number = |c: &&Cell| match c {
            Cell::Num(x) => Some(*x),
            Cell::Text(_) => None,
        };
        let empty = |c: &&Cell| matches!(c, Cell::Text(s) if s.is_empty());
        let numbers: Vec<Option<f64>> = cells.iter().map(number).collect();
        if !cells.is_empty() && numbers.iter().all(Option::is_some) {
            let whole = |x: &f64| x.fract() == 0.0 && x.abs() < EXACT_INTEGER;
            let values: Vec<f64> = numbers.into_iter().flatten().collect();
            if values.iter().all(whole) {
                return Column::Integers(values.iter().map(|&x| x as i64).collect());
            }
            return Column::Numbers(values);
        }
        if !cells.is_empty() && cells.iter().all(|c| number(c).is_some() || empty(c)) {
            return Column::Numbers(numbers.iter().map(|x| x.unwrap_or(f64::NAN)).collect());
        }
        let text = |c: &&Cell| match c {
            Cell::Num(x) => show(*x),
            Cell::Text(s) => s.clone(),
        };
        let flags: Vec<Option<bool>> = (cells.iter())
            .map(|c| match c {
                Cell::Text(s) if s == "true" => Some(true),
                Cell::Text(s) if s == "false" => Some(false),
                _ => None,
            })
            .collect();
        if !cells.is_empty() && flags.iter().all(Option::is_some) {
            return Column::Booleans(flags.into_iter().flatten().collect());
        }
        Column::Texts(
            (cells.iter())
                .map(|c| (!empty(c)).then(|| text(c)))
                .collect(),
        )
    }
}

impl Table {
    /// Every column, by name, in the header's order.
    pub fn columns(&self) -> Vec<(&str, Column)> {
        (self.header.iter().enumerate())
            .map(|(k, name)| (name.as_str(), Column::of(self, k)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(cells: Vec<Cell>) -> Table {
        Table {
            header: vec!["c".into()],
            rows: cells.into_iter().map(|c| vec![c]).collect(),
        }
    }

    fn text(s: &str) -> Cell {
        Cell::Text(s.into())
    }

    #[test]
    fn a_column_is_typed_as_a_csv_reader_types_it() {
        let of = |cells| Column::of(&table(cells), 0);
        assert_eq!(
            of(vec![Cell::Num(2.0), Cell::Num(-3.0)]),
            Column::Integers(vec![2, -3])
        );
        assert_eq!(
            of(vec![Cell::Num(2.0), Cell::Num(0.5)]),
            Column::Numbers(vec![2.0, 0.5])
        );
        assert_eq!(
            of(vec![Cell::Num(1e300)]),
            Column::Numbers(vec![1e300]),
            "a whole number beyond 2^53 is no exact integer"
        );
        match of(vec![Cell::Num(2.0), text("")]) {
            Column::Numbers(v) => assert!(v[0] == 2.0 && v[1].is_nan(), "{v:?}"),
            other => panic!("{other:?}"),
        }
        match of(vec![text(""), text("")]) {
            Column::Numbers(v) => assert!(v.iter().all(|x| x.is_nan()), "{v:?}"),
            other => panic!("{other:?}"),
        }
        assert_eq!(
            of(vec![text("true"), text("false")]),
            Column::Booleans(vec![true, false])
        );
        assert_eq!(
            of(vec![text("ok"), text(""), Cell::Num(0.1)]),
            Column::Texts(vec![Some("ok".into()), None, Some("0.1".into())])
        );
        assert_eq!(
            of(vec![text("true"), text("")]),
            Column::Texts(vec![Some("true".into()), None])
        );
        assert_eq!(of(vec![]), Column::Texts(vec![]));
    }
}
