//! A long TOML system file read in parts: the file is cut before every [`PART_TABLES`]-th
//! `[[body]]`, `[[anchor]]`, `[[spring]]`, `[[contact]]`, `[[force]]` or `[[controller]]`
//! header, each part is
//! a TOML document of its own, and the parts' tables are appended in order. A whole-document
//! parse holds about 50 bytes of memory a byte of text; a part holds a few hundred kilobytes,
//! so a file of 10⁶ bodies reads in the memory of its system (docs/performance.md).

use toml_parser::lexer::TokenKind;
use toml_parser::Source;

/// The tables of a system file that are arrays of tables, the places where it may be cut.
const ARRAY_TABLES: [&str; 6] = ["body", "anchor", "spring", "contact", "force", "controller"];

/// How many array-table headers one part holds.
pub const PART_TABLES: usize = 1024;

/// The byte offsets at which `text` may be cut into documents that parse alone: the start of
/// each line that opens a `[[body]]`, `[[anchor]]`, `[[spring]]`, `[[contact]]`, `[[force]]`
/// or `[[controller]]` table. `None` where one of those names is also a root key or a standard table
/// (`body = [...]`, `[body]`): such a file is read whole, so that TOML's rule against
/// extending a static array or a table with `[[...]]` still applies.
pub fn cut_points(text: &str) -> Option<Vec<usize>> {
    let mut lexer = Source::new(text).lex().peekable();
    let mut cuts = Vec::new();
    let mut depth = 0usize; // open `[` and `{` of values
    let mut line_start = Some(0usize); // the offset of the line, while at its start at depth 0
    let mut seen_header = false;
    while let Some(token) = lexer.next() {
        let kind = token.kind();
        let span = token.span();
        match (line_start, kind) {
            (_, TokenKind::Eof) => break,
            (Some(_), TokenKind::Whitespace | TokenKind::Comment) => {}
            (_, TokenKind::Newline) if depth == 0 => line_start = Some(span.end()),
            (Some(line), TokenKind::LeftSquareBracket) => {
                let array = lexer
                    .peek()
                    .is_some_and(|t| t.kind() == TokenKind::LeftSquareBracket);
                let mut key = Vec::new();
                line_start = Some(text.len());
                for t in lexer.by_ref() {
                    match t.kind() {
                        TokenKind::Newline | TokenKind::Eof => {
                            line_start = Some(t.span().end());
                            break;
                        }
                        TokenKind::LeftSquareBracket
                        | TokenKind::RightSquareBracket
                        | TokenKind::Whitespace
                        | TokenKind::Comment => {}
                        _ => key.push(unquoted(&text[t.span().start()..t.span().end()])),
                    }
                }
                let table = matches!(key.as_slice(), [name] if ARRAY_TABLES.contains(name));
                match (table, array) {
                    (true, true) => cuts.push(line),
                    (true, false) => return None,
                    (false, _) => {}
                }
                seen_header = true;
            }
            (Some(_), _) => {
                let word = unquoted(&text[span.start()..span.end()]);
                if !seen_header && ARRAY_TABLES.contains(&word) {
                    return None;
                }
                line_start = None;
            }
            (None, TokenKind::LeftSquareBracket | TokenKind::LeftCurlyBracket) => depth += 1,
            (None, TokenKind::RightSquareBracket | TokenKind::RightCurlyBracket) => {
                depth = depth.saturating_sub(1)
            }
            (None, _) => {}
        }
    }
    Some(cuts)
}

/// A key as written, without the quotes of a quoted key.
fn unquoted(word: &str) -> &str {
    word.trim_matches(|c| c == '"' || c == '\'')
}

/// The parts of `text`: its pieces between every [`PART_TABLES`]-th cut point, the root keys
/// in the first.
pub fn parts(text: &str) -> Vec<(usize, &str)> {
    let cuts = cut_points(text).unwrap_or_default();
    let mut starts: Vec<usize> = std::iter::once(0)
        .chain(cuts.into_iter().skip(PART_TABLES).step_by(PART_TABLES))
        .collect();
    starts.push(text.len());
    starts
        .windows(2)
        .map(|w| (w[0], &text[w[0]..w[1]]))
        .collect()
}

/// The message of a TOML error in the part at `offset` of `text`, with line and column in the
/// whole file, as the `toml` crate renders them.
pub fn message(text: &str, offset: usize, error: &toml::de::Error) -> String {
    let Some(span) = error.span() else {
        return error.to_string().trim().to_string();
    };
    let start = (offset + span.start).min(text.len());
    let line_start = text[..start].rfind('\n').map_or(0, |n| n + 1);
    let line = text[..line_start].matches('\n').count() + 1;
    let column = text[line_start..start].chars().count();
    let content = text[line_start..].split('\n').next().unwrap_or("");
    let width = (span.end - span.start)
        .min(content.len().saturating_sub(column))
        .max(1);
    let gutter = " ".repeat(line.to_string().len() + 1);
    format!(
        "TOML parse error at line {line}, column {}\n{gutter}|\n{line} | {content}\n{gutter}|{}{}\n{}",
        column + 1,
        " ".repeat(column + 1),
        "^".repeat(width),
        error.message()
    )
    .trim()
    .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuts_fall_on_array_table_headers_only() {
        let text = "param_set = \"paper\"\n\
                    [[body]]\nname = \"a\"\nm = 1\n\
                    [contact.params]\n\
                    x = \"\"\"\n[[body]]\n\"\"\"\n\
                    y = [\n  [1],\n[[2]]]\n\
                    [[ spring ]] # comment\nk = 1\n\
                    [[\"force\"]]\n\
                    [[body.z]]\n";
        let lines: Vec<usize> = cut_points(text)
            .unwrap()
            .iter()
            .map(|&c| text[..c].matches('\n').count() + 1)
            .collect();
        // `[[body]]` (line 2), `[[ spring ]]` (12) and `[["force"]]` (14); not the header in
        // the multi-line string (7), the nested array (11) or the dotted `[[body.z]]` (15).
        assert_eq!(lines, [2, 12, 14]);
    }

    #[test]
    fn a_root_key_or_table_of_an_array_name_keeps_the_file_whole() {
        assert_eq!(cut_points("body = []\n[[body]]\n"), None);
        assert_eq!(cut_points("spring.k = 1\n"), None);
        assert_eq!(cut_points("[[body]]\n[contact]\n"), None);
        // The same name as a key inside a table is no root key.
        assert_eq!(cut_points("[[contact]]\nbody = \"a\"\n"), Some(vec![0]));
    }

    #[test]
    fn parts_hold_a_thousand_tables_each() {
        let text = "[[body]]\n".repeat(2 * PART_TABLES + 1);
        let parts = parts(&text);
        let starts: Vec<usize> = parts.iter().map(|p| p.0).collect();
        assert_eq!(starts, [0, 9 * PART_TABLES, 18 * PART_TABLES]);
        assert_eq!(parts.iter().map(|p| p.1.len()).sum::<usize>(), text.len());
    }
}
