//! Reads polynomial expressions in `u` and `v` into exact [`Polynomial`]s
//! ([`parse_polynomial`]).

use super::monomial::{Polynomial, MAX_DEGREE};
use crate::error::{Error, Result};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Num, Zero};

const MAX_DEPTH: usize = 200;
const MAX_DECIMAL_EXPONENT: i64 = 10_000;

/// Parses an expression in `u` and `v` into an exact [`Polynomial`].
///
/// # Grammar
/// ```text
/// expr   := term (('+' | '-') term)*
/// term   := unary (('*' | '/') unary)*
/// unary  := ('+' | '-') unary | power
/// power  := atom ('^' integer)?
/// atom   := number | 'u' | 'v' | '(' expr ')'
/// number := digits ['.' digits] [('e' | 'E') ['+' | '-'] digits]
/// ```
/// Numbers are read exactly (`0.1` is 1/10, `2.5e-3` is 1/400). Division is by
/// non-zero constants only. `-u^2` is `-(u^2)`. Errors name what is wrong and the
/// byte offset; nothing panics. Limits: nesting depth 200, exponents and
/// total degree up to 200, decimal
/// exponents up to ±10000.
///
/// ```
/// use rootclip::parse_polynomial;
/// let p = parse_polynomial("10*(u-1/2)*(u-1/4)*(u-1/8) + 1/4 - v").unwrap();
/// assert_eq!(p.total_degree(), 3);
/// assert!(parse_polynomial("u^-1").is_err());
/// ```
pub fn parse_polynomial(src: &str) -> Result<Polynomial> {
    let mut p = Parser {
        src: src.as_bytes(),
        pos: 0,
        depth: 0,
    };
    p.skip_ws();
    if p.pos == p.src.len() {
        return Err(p.error("empty expression"));
    }
    let poly = p.expr()?;
    p.skip_ws();
    if p.pos < p.src.len() {
        let what = p.describe_here();
        return Err(p.error(&format!("unexpected {what} (expected an operator or end of input)")));
    }
    Ok(poly)
}

struct Parser<'a> {
    src: &'a [u8],
    pos: usize,
    depth: usize,
}

impl Parser<'_> {
    fn error(&self, message: &str) -> Error {
        Error::Parse {
            message: message.to_string(),
            at: self.pos,
        }
    }

    fn skip_ws(&mut self) {
        while self.pos < self.src.len() && self.src[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.src.get(self.pos).copied()
    }

    fn describe_here(&self) -> String {
        match std::str::from_utf8(&self.src[self.pos..])
            .ok()
            .and_then(|s| s.chars().next())
        {
            Some(c) => format!("'{c}'"),
            None => "end of input".to_string(),
        }
    }

    fn expr(&mut self) -> Result<Polynomial> {
        let mut acc = self.term()?;
        while let Some(op @ (b'+' | b'-')) = self.peek() {
            self.pos += 1;
            let rhs = self.term()?;
            acc = if op == b'+' { acc.add(&rhs) } else { acc.sub(&rhs) };
        }
        Ok(acc)
    }

    fn term(&mut self) -> Result<Polynomial> {
        let mut acc = self.unary()?;
        while let Some(op @ (b'*' | b'/')) = self.peek() {
            let at = self.pos;
            self.pos += 1;
            let rhs = self.unary()?;
            acc = if op == b'*' {
                acc.mul(&rhs).map_err(|e| self.at(e, at))?
            } else {
                match rhs.as_constant() {
                    Some(c) if c.is_zero() => {
                        return Err(Error::Parse {
                            message: "division by zero".into(),
                            at,
                        })
                    }
                    Some(c) => acc.scale(&c.recip()),
                    None => {
                        return Err(Error::Parse {
                            message: "division by a non-constant expression (only constants may divide)".into(),
                            at,
                        })
                    }
                }
            };
        }
        Ok(acc)
    }

    fn at(&self, e: Error, at: usize) -> Error {
        match e {
            Error::TooLarge(message) => Error::Parse { message, at },
            other => other,
        }
    }

    fn unary(&mut self) -> Result<Polynomial> {
        match self.peek() {
            Some(b'-') => {
                self.pos += 1;
                self.nested(|p| p.unary()).map(|x| x.neg())
            }
            Some(b'+') => {
                self.pos += 1;
                self.nested(|p| p.unary())
            }
            _ => self.power(),
        }
    }

    fn nested(&mut self, f: impl FnOnce(&mut Self) -> Result<Polynomial>) -> Result<Polynomial> {
        if self.depth >= MAX_DEPTH {
            return Err(self.error(&format!("nesting deeper than {MAX_DEPTH}")));
        }
        self.depth += 1;
        let out = f(self);
        self.depth -= 1;
        out
    }

    fn power(&mut self) -> Result<Polynomial> {
        let base = self.atom()?;
        if self.peek() != Some(b'^') {
            return Ok(base);
        }
        let at = self.pos;
        self.pos += 1;
        let e = self.exponent()?;
        if self.peek() == Some(b'^') {
            return Err(self.error("chained '^' is ambiguous; use parentheses"));
        }
        base.pow(e).map_err(|err| self.at(err, at))
    }

    fn exponent(&mut self) -> Result<u32> {
        match self.peek() {
            Some(c) if c.is_ascii_digit() => {}
            Some(b'-') => return Err(self.error("exponent must be a non-negative integer (found '-')")),
            _ => {
                let what = self.describe_here();
                return Err(self.error(&format!("expected an integer exponent after '^', found {what}")));
            }
        }
        let start = self.pos;
        let digits = self.digits();
        if self.src.get(self.pos) == Some(&b'.') {
            return Err(self.error("exponent must be an integer"));
        }
        match digits.parse::<u32>() {
            Ok(e) if e <= MAX_DEGREE => Ok(e),
            _ => Err(Error::Parse {
                message: format!("exponent {digits} exceeds the limit {MAX_DEGREE}"),
                at: start,
            }),
        }
    }

    fn digits(&mut self) -> String {
        let start = self.pos;
        while self.pos < self.src.len() && self.src[self.pos].is_ascii_digit() {
            self.pos += 1;
        }
        String::from_utf8_lossy(&self.src[start..self.pos]).into_owned()
    }

    fn atom(&mut self) -> Result<Polynomial> {
        match self.peek() {
            None => Err(self.error("unexpected end of input (expected a number, u, v or '(')")),
            Some(b'(') => {
                let open = self.pos;
                self.pos += 1;
                let inner = self.nested(|p| p.expr())?;
                if self.peek() != Some(b')') {
                    let what = self.describe_here();
                    return Err(self.error(&format!("expected ')' to close '(' at offset {open}, found {what}")));
                }
                self.pos += 1;
                Ok(inner)
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() || c == b'_' => {
                let start = self.pos;
                while self.pos < self.src.len()
                    && (self.src[self.pos].is_ascii_alphanumeric() || self.src[self.pos] == b'_')
                {
                    self.pos += 1;
                }
                match &self.src[start..self.pos] {
                    b"u" => Ok(Polynomial::u()),
                    b"v" => Ok(Polynomial::v()),
                    name => Err(Error::Parse {
                        message: format!("unknown variable '{}' (only u and v)", String::from_utf8_lossy(name)),
                        at: start,
                    }),
                }
            }
            Some(_) => {
                let what = self.describe_here();
                Err(self.error(&format!("unexpected {what} (expected a number, u, v or '(')")))
            }
        }
    }

    fn number(&mut self) -> Result<Polynomial> {
        let start = self.pos;
        let int_part = self.digits();
        let mut frac = String::new();
        if self.src.get(self.pos) == Some(&b'.') {
            self.pos += 1;
            frac = self.digits();
        }
        if int_part.is_empty() && frac.is_empty() {
            return Err(Error::Parse {
                message: "a lone '.' is not a number".into(),
                at: start,
            });
        }
        let mut exp: i64 = 0;
        if matches!(self.src.get(self.pos), Some(b'e' | b'E')) {
            let e_at = self.pos;
            self.pos += 1;
            let neg = match self.src.get(self.pos) {
                Some(b'-') => {
                    self.pos += 1;
                    true
                }
                Some(b'+') => {
                    self.pos += 1;
                    false
                }
                _ => false,
            };
            let d = self.digits();
            match d.parse::<i64>() {
                Ok(x) if x <= MAX_DECIMAL_EXPONENT => exp = if neg { -x } else { x },
                Ok(_) => {
                    return Err(Error::Parse {
                        message: format!("decimal exponent beyond ±{MAX_DECIMAL_EXPONENT}"),
                        at: e_at,
                    })
                }
                Err(_) => {
                    return Err(Error::Parse {
                        message: "expected digits after the exponent marker".into(),
                        at: e_at,
                    })
                }
            }
        }
        let mantissa = BigInt::from_str_radix(&format!("{int_part}{frac}0"), 10).expect("digits") / BigInt::from(10);
        let scale = exp - frac.len() as i64;
        let ten = BigInt::from(10);
        let value = if scale >= 0 {
            BigRational::from_integer(mantissa * num_traits::pow(ten, scale as usize))
        } else {
            BigRational::new(mantissa, num_traits::pow(ten, (-scale) as usize))
        };
        Ok(Polynomial::constant(value))
    }
}
