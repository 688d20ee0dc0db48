//! The library's errors as Python exceptions: `PermissionError` (an `OSError`) when the
//! file policy refuses a file (not a regular file, outside the allowed root, larger than
//! the cap), `OSError` when a file could not be read or written, [`ToleranceUnreachableError`] (a `ValueError`) when a sphere-tree cannot meet
//! the tolerance asked for, `ValueError` for everything else (bad input), with the
//! library's message.

use pyo3::PyErr;
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyPermissionError, PyValueError};
use sphaera::io::{FileRefusal, IoError, ParseReason};

create_exception!(
    sphaera,
    ToleranceUnreachableError,
    PyValueError,
    "A sphere-tree cannot meet the tolerance asked for within the library's limits (nodes, \
levels): the message gives the tolerance, the worst certified leaf error reached and the \
spheres and levels built; the attributes `tolerance`, `worst`, `spheres` and `levels` \
hold them. A `ValueError`: ask for a larger tolerance."
);

/// `PermissionError` when the file policy refused a file anywhere in `error`'s chain,
/// `OSError` when an I/O error is, else `ValueError`; the message is the library's.
pub fn to_py(error: &(dyn std::error::Error + 'static)) -> PyErr {
    let mut io = false;
    let mut refused = false;
    let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(error);
    while let Some(e) = cause {
        io |= e.is::<std::io::Error>();
        refused |= e.is::<FileRefusal>();
        refused |= matches!(
            e.downcast_ref::<IoError>(),
            Some(
                IoError::Refused { .. }
                    | IoError::Parse {
                        reason: ParseReason::BufferRefused { .. },
                        ..
                    }
            )
        );
        cause = e.source();
    }
    let message = error.to_string();
    if refused {
        PyPermissionError::new_err(message)
    } else if io {
        PyOSError::new_err(message)
    } else {
        PyValueError::new_err(message)
    }
}

/// [`to_py`] for a `Result`'s error.
pub trait IntoPy<T> {
    /// The value, or the error as a Python exception.
    fn py_err(self) -> Result<T, PyErr>;
}

impl<T, E: std::error::Error + 'static> IntoPy<T> for Result<T, E> {
    fn py_err(self) -> Result<T, PyErr> {
        self.map_err(|e| to_py(&e))
    }
}

/// A `ValueError` with `message`.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}
