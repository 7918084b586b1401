//! Splits SWP text into tokens with positions.

use super::SourcePos;

/// What a token is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TokenKind {
    /// `[`
    Open,
    /// `]`
    Close,
    /// Any other run of non-whitespace characters (keyword, name, number, option).
    Word,
}

/// One token, borrowing its text from the input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Token<'a> {
    /// What the token is.
    pub kind: TokenKind,
    /// The token's text (`"["` and `"]"` for brackets).
    pub text: &'a str,
    /// Where the token starts.
    pub pos: SourcePos,
    /// The position just after the token's last character.
    pub end: SourcePos,
}

/// SWP whitespace: what C's `isspace` accepts in the "C" locale.
pub(crate) fn is_space(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\n' | '\r' | '\u{b}' | '\u{c}')
}

/// Splits `text` into tokens. Never fails: every character is whitespace, part of a comment,
/// a bracket, or part of a word.
///
/// A byte order mark at the very start is skipped and does not count as a column. `#` starts a
/// comment that runs to the end of the line, wherever it appears.
pub(crate) fn tokenize(text: &str) -> Vec<Token<'_>> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut tokens = Vec::new();
    let mut line = 1usize;
    let mut column = 1usize;
    // Start (byte offset, position) of the word being read, if any.
    let mut word: Option<(usize, SourcePos)> = None;
    let mut in_comment = false;

    for (i, c) in body.char_indices() {
        let here = SourcePos::new(line, column);
        if in_comment {
            in_comment = c != '\n';
        } else if is_space(c) || c == '[' || c == ']' || c == '#' {
            if let Some((start, pos)) = word.take() {
                tokens.push(Token {
                    kind: TokenKind::Word,
                    text: body.get(start..i).unwrap_or_default(),
                    pos,
                    end: here,
                });
            }
            let kind = match c {
                '[' => Some(TokenKind::Open),
                ']' => Some(TokenKind::Close),
                _ => None,
            };
            if let Some(kind) = kind {
                tokens.push(Token {
                    kind,
                    text: body.get(i..i + 1).unwrap_or_default(),
                    pos: here,
                    end: SourcePos::new(line, column + 1),
                });
            }
            in_comment = c == '#';
        } else if word.is_none() {
            word = Some((i, here));
        }
        if c == '\n' {
            line += 1;
            column = 1;
        } else {
            column += 1;
        }
    }
    if let Some((start, pos)) = word {
        tokens.push(Token {
            kind: TokenKind::Word,
            text: body.get(start..).unwrap_or_default(),
            pos,
            end: SourcePos::new(line, column),
        });
    }
    tokens
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(text: &str) -> Vec<&str> {
        tokenize(text).iter().map(|t| t.text).collect()
    }

    #[test]
    fn brackets_split_words() {
        assert_eq!(texts("[3 0]"), ["[", "3", "0", "]"]);
        assert_eq!(texts("[ 3 0 ]"), ["[", "3", "0", "]"]);
        assert_eq!(texts("[-2 2] [-4 0]"), ["[", "-2", "2", "]", "[", "-4", "0", "]"]);
        assert_eq!(texts("a]b[c"), ["a", "]", "b", "[", "c"]);
    }

    #[test]
    fn whitespace_and_comments() {
        assert_eq!(texts("bez2\t.\r\n20  4 \u{b}\u{c}x"), ["bez2", ".", "20", "4", "x"]);
        assert_eq!(texts("a # b c\nd#e\n#f\ng"), ["a", "d", "g"]);
        assert_eq!(texts("[1 2]# note"), ["[", "1", "2", "]"]);
        assert!(texts("").is_empty());
        assert!(texts(" \r\n \n# only a comment").is_empty());
    }

    #[test]
    fn positions_count_lines_and_chars() {
        let tokens = tokenize("bez2 .\r\n  [é2 x]\nlast");
        let pos: Vec<_> = tokens.iter().map(|t| (t.text, t.pos.line, t.pos.column, t.end.line, t.end.column)).collect();
        assert_eq!(
            pos,
            [
                ("bez2", 1, 1, 1, 5),
                (".", 1, 6, 1, 7),
                ("[", 2, 3, 2, 4),
                ("é2", 2, 4, 2, 6),
                ("x", 2, 7, 2, 8),
                ("]", 2, 8, 2, 9),
                ("last", 3, 1, 3, 5),
            ]
        );
    }

    #[test]
    fn byte_order_mark_is_skipped() {
        let tokens = tokenize("\u{feff}circ . 3 1");
        assert_eq!(tokens[0].text, "circ");
        assert_eq!(tokens[0].pos, SourcePos::new(1, 1));
    }
}
