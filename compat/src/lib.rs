//! `yade._ryade`: the pyo3 extension behind the `yade` compatibility package.
//!
//! The Python layer only translates YADE's API; every piece of physics stays in the `ryade` crate.
//! State is addressed by body id and field name so that Python can build YADE's live views
//! (`b.state.vel[2] = 0.1`) on top. A step is driven in segments (`advance`) so that Python engines
//! (PyRunner) run between built-in engines without holding a borrow of the scene.

use pyo3::exceptions::{PyIndexError, PyKeyError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple, PyType};
use pyo3::{ffi, intern};
use ryade::io::scene_json;
use ryade::math::{Quat, Vec3};
use ryade::scene::{Engine, Scene};
use ryade::shape::Shape;
use serde_json::Value;
use std::collections::HashMap;

type V3 = (f64, f64, f64);

fn v3(v: &Vec3) -> V3 {
    (v[0], v[1], v[2])
}

fn vec(t: V3) -> Vec3 {
    Vec3::new(t.0, t.1, t.2)
}

/// Steps run between two checks for a Python signal (Ctrl-C, SIGTERM) in `run_steps`.
const SIGNAL_CHECK_STEPS: u64 = 256;

fn err<E: std::fmt::Display>(e: E) -> PyErr {
    PyRuntimeError::new_err(format!("{:#}", e))
}

#[pyclass]
struct Sim {
    scene: Scene,
    saved: HashMap<String, Scene>,
    /// Next engine to run in the step in progress (None: between steps).
    cursor: Option<usize>,
    /// `yade.minieigen.Vector3`, for the values built here (`_set_vector3`).
    vector3: Option<Vec3Type>,
}

/// The per-body vector fields of `State` addressed by the fast paths.
#[derive(Clone, Copy)]
enum VecField {
    Pos,
    Vel,
    AngVel,
    Inertia,
    AngMom,
}

impl VecField {
    fn parse(name: &str) -> Option<VecField> {
        Some(match name {
            "pos" => VecField::Pos,
            "vel" => VecField::Vel,
            "angVel" => VecField::AngVel,
            "inertia" => VecField::Inertia,
            "angMom" => VecField::AngMom,
            _ => return None,
        })
    }
    fn no_such(name: &str) -> PyErr {
        PyKeyError::new_err(format!("State has no vector attribute '{}' in ryade", name))
    }
}

/// `yade.minieigen.Vector3`, the pure-Python class of the values the fast paths make and read, with
/// where its three slots (`_v` the coefficient list or None for a view, `_g`/`_s` a view's getter and
/// setter or None) lie in an instance. The offsets are found at run time (`Vec3Type::new`) by
/// storing marker objects through the slots' own descriptors and looking for them; a layout that
/// does not match (a `__dict__`, a slot missing or found twice) leaves them unset and every access
/// then goes through getattr/setattr.
struct Vec3Type {
    tp: Py<PyType>,
    slots: Option<[isize; 3]>,
}

const V: usize = 0;
const G: usize = 1;
const SLOT_NAMES: [&str; 3] = ["_v", "_g", "_s"];

/// A new, zero-filled, unset instance of the Python class `tp` (what `object.__new__(tp)` makes).
fn alloc_instance<'py>(tp: &Bound<'py, PyType>) -> PyResult<Bound<'py, PyAny>> {
    // SAFETY: PyType_GenericAlloc is the tp_alloc of a Python class; it returns a new reference
    // (NULL with an exception set on failure), which from_owned_ptr_or_err takes over.
    unsafe { Bound::from_owned_ptr_or_err(tp.py(), ffi::PyType_GenericAlloc(tp.as_type_ptr(), 0)) }
}

impl Vec3Type {
    fn new(tp: &Bound<'_, PyType>) -> PyResult<Vec3Type> {
        let py = tp.py();
        let basic: isize = tp.getattr("__basicsize__")?.extract()?;
        let dict: isize = tp.getattr("__dictoffset__")?.extract()?;
        let mut slots = None;
        if dict == 0 {
            let obj = alloc_instance(tp)?;
            let marks = [PyList::empty(py), PyList::empty(py), PyList::empty(py)];
            for (name, m) in SLOT_NAMES.iter().zip(&marks) {
                obj.setattr(*name, m)?;
            }
            let word = std::mem::size_of::<*mut ffi::PyObject>() as isize;
            let head = std::mem::size_of::<ffi::PyObject>() as isize;
            let mut found = [None; 3];
            let mut ok = true;
            let mut off = head;
            while off + word <= basic {
                // SAFETY: off + word <= tp_basicsize: a word of the instance's memory
                let p = unsafe {
                    *(obj.as_ptr() as *const u8)
                        .offset(off)
                        .cast::<*mut ffi::PyObject>()
                };
                for (k, m) in marks.iter().enumerate() {
                    if p == m.as_ptr() {
                        ok &= found[k].replace(off).is_none();
                    }
                }
                off += word;
            }
            if let (true, [Some(v), Some(g), Some(s)]) = (ok, found) {
                slots = Some([v, g, s]);
            }
        }
        Ok(Vec3Type {
            tp: tp.clone().unbind(),
            slots,
        })
    }

    /// A new instance with its slots `_v`, `_g`, `_s` set to `vals` (consumed).
    fn make<'py>(
        &self,
        py: Python<'py>,
        vals: [Bound<'py, PyAny>; 3],
    ) -> PyResult<Bound<'py, PyAny>> {
        let obj = alloc_instance(self.tp.bind(py))?;
        match self.slots {
            Some(offs) => {
                for (off, v) in offs.iter().zip(vals) {
                    // SAFETY: a slot of a fresh instance (NULL, nothing to release), found by Vec3Type::new;
                    // the slot takes over the reference
                    unsafe {
                        *(obj.as_ptr() as *mut u8)
                            .offset(*off)
                            .cast::<*mut ffi::PyObject>() = v.into_ptr()
                    };
                }
            }
            None => {
                for (name, v) in SLOT_NAMES.iter().zip(vals) {
                    obj.setattr(*name, v)?;
                }
            }
        }
        Ok(obj)
    }

    /// A new Vector3 holding `v`: what `Vector3._new([x, y, z])` makes, without running Python code.
    fn plain<'py>(&self, py: Python<'py>, v: V3) -> PyResult<Bound<'py, PyAny>> {
        self.make(
            py,
            [
                PyList::new(py, [v.0, v.1, v.2])?.into_any(),
                py.None().into_bound(py),
                py.None().into_bound(py),
            ],
        )
    }

    /// A live Vector3 view of a body's vector field (what `Vector3._view(get, set)` makes): its `_g`
    /// and `_s` are one `FieldAccess`.
    fn view<'py>(&self, py: Python<'py>, acc: FieldAccess) -> PyResult<Bound<'py, PyAny>> {
        let acc = Bound::new(py, acc)?.into_any();
        self.make(py, [py.None().into_bound(py), acc.clone(), acc])
    }
}

/// `f(first, *args, **kw)` from a METH_FASTCALL argument vector (`nargs` positional arguments at
/// `args`, then one value per name in the `kwnames` tuple, or none when it is NULL); `f` is
/// consumed. Returns a new reference, NULL with the exception set on failure.
///
/// # Safety
/// GIL held; `f` a new reference (or NULL with an exception set), `first` NULL or a borrowed object,
/// `args`/`nargs`/`kwnames` as CPython passes them to a METH_FASTCALL function.
unsafe fn call_fastcall(
    f: *mut ffi::PyObject,
    first: *mut ffi::PyObject,
    args: *mut *mut ffi::PyObject,
    nargs: ffi::Py_ssize_t,
    kwnames: *mut ffi::PyObject,
) -> *mut ffi::PyObject {
    if f.is_null() {
        return f;
    }
    let lead = if first.is_null() { 0 } else { 1 };
    let t = ffi::PyTuple_New(nargs + lead);
    if t.is_null() {
        ffi::Py_DECREF(f);
        return t;
    }
    if lead == 1 {
        ffi::Py_INCREF(first);
        ffi::PyTuple_SetItem(t, 0, first);
    }
    for k in 0..nargs {
        let a = *args.offset(k);
        ffi::Py_INCREF(a);
        ffi::PyTuple_SetItem(t, k + lead, a);
    }
    let mut kw = std::ptr::null_mut();
    if !kwnames.is_null() {
        kw = ffi::PyDict_New();
        let ok = !kw.is_null()
            && (0..ffi::PyTuple_Size(kwnames)).all(|k| {
                ffi::PyDict_SetItem(
                    kw,
                    ffi::PyTuple_GetItem(kwnames, k),
                    *args.offset(nargs + k),
                ) == 0
            });
        if !ok {
            ffi::Py_XDECREF(kw);
            ffi::Py_DECREF(t);
            ffi::Py_DECREF(f);
            return std::ptr::null_mut();
        }
    }
    let r = ffi::PyObject_Call(f, t, kw);
    ffi::Py_XDECREF(kw);
    ffi::Py_DECREF(t);
    ffi::Py_DECREF(f);
    r
}

// ---- Vector3.__getitem__ in C

/// The classes whose `__getitem__` is `vector_getitem` (a class object, kept alive so that its
/// address is never reused, with its slot offsets and length). Appended to by
/// `_install_vector_getitem` (a new list replaces the old one, which is leaked: a few per process);
/// read by `vector_getitem` with the GIL held.
type GetitemClasses = Vec<(Py<PyType>, [isize; 3], isize)>;
static GETITEM_CLASSES: std::sync::atomic::AtomicPtr<GetitemClasses> =
    std::sync::atomic::AtomicPtr::new(std::ptr::null_mut());

/// Slot `off` of `obj` (borrowed; NULL when unset).
///
/// # Safety
/// `obj` is an instance of a class whose slots lie at `off` (`Vec3Type::new`).
unsafe fn slot_ptr(obj: *mut ffi::PyObject, off: isize) -> *mut ffi::PyObject {
    *(obj as *const u8).offset(off).cast::<*mut ffi::PyObject>()
}

/// `__getitem__` of the registered vector classes, with their Python definition's effect: for an
/// exact int `i` in `0..N`, `self._v[i]` (a plain value) or `self._g()[i]` (a view); anything else
/// (negative or out-of-range indices, slices, subclass instances) calls the Python definition,
/// `type(self)._py_getitem(self, i)`, which raises minieigen's errors.
///
/// # Safety
/// Called by CPython as a METH_FASTCALL method (`slf`, `nargs` arguments at `args`), GIL held.
unsafe extern "C" fn vector_getitem(
    slf: *mut ffi::PyObject,
    args: *mut *mut ffi::PyObject,
    nargs: ffi::Py_ssize_t,
) -> *mut ffi::PyObject {
    let classes = GETITEM_CLASSES.load(std::sync::atomic::Ordering::Acquire);
    if nargs == 1 && !classes.is_null() {
        let i = *args;
        let tp = ffi::Py_TYPE(slf);
        if let Some((_, offs, n)) = (*classes)
            .iter()
            .find(|c| c.0.as_ptr() as *mut ffi::PyTypeObject == tp)
        {
            if ffi::PyLong_CheckExact(i) != 0 {
                let mut overflow = 0;
                let k = ffi::PyLong_AsLongAndOverflow(i, &mut overflow) as isize;
                if overflow == 0 && (0..*n).contains(&k) {
                    let g = slot_ptr(slf, offs[G]);
                    let v = slot_ptr(slf, offs[V]);
                    if g == ffi::Py_None()
                        && !v.is_null()
                        && ffi::PyList_CheckExact(v) != 0
                        && ffi::PyList_Size(v) == *n
                    {
                        let item = ffi::PyList_GetItem(v, k);
                        ffi::Py_INCREF(item);
                        return item;
                    }
                    if !g.is_null() && g != ffi::Py_None() {
                        let t = ffi::PyObject_CallNoArgs(g);
                        if t.is_null() {
                            return t;
                        }
                        let r = ffi::PyObject_GetItem(t, i);
                        ffi::Py_DECREF(t);
                        return r;
                    }
                }
            }
        }
    }
    // the Python definition: type(slf)._py_getitem(slf, *args)
    let f = ffi::PyObject_GetAttrString(
        ffi::Py_TYPE(slf) as *mut ffi::PyObject,
        c"_py_getitem".as_ptr(),
    );
    call_fastcall(f, slf, args, nargs, std::ptr::null_mut())
}

/// `_install_vector_getitem(cls, n)`: a method descriptor calling `vector_getitem`, for
/// `cls.__getitem__` (the Python definition must be kept as `cls._py_getitem`); `cls` is a
/// minieigen vector class of length `n` with the slots `_v`, `_g`, `_s`. Returns None (and
/// registers nothing) when those slots cannot be located.
#[pyfunction]
fn _install_vector_getitem(
    py: Python<'_>,
    cls: &Bound<'_, PyType>,
    n: isize,
) -> PyResult<PyObject> {
    let Some(offs) = Vec3Type::new(cls)?.slots else {
        return Ok(py.None());
    };
    // SAFETY: the list is only replaced (never freed) and read with the GIL held, which this holds
    let old = GETITEM_CLASSES.load(std::sync::atomic::Ordering::Acquire);
    let mut list: GetitemClasses = if old.is_null() {
        Vec::new()
    } else {
        unsafe {
            (*old)
                .iter()
                .map(|(t, o, n)| (t.clone_ref(py), *o, *n))
                .collect()
        }
    };
    list.push((cls.clone().unbind(), offs, n));
    GETITEM_CLASSES.store(
        Box::into_raw(Box::new(list)),
        std::sync::atomic::Ordering::Release,
    );
    // a method descriptor of `object`, so that it applies to every instance (the function checks
    // the class itself)
    fastcall_descriptor(
        py,
        std::ptr::addr_of_mut!(ffi::PyBaseObject_Type),
        c"__getitem__",
        vector_getitem,
        c"v[i] (yade._ryade.vector_getitem; the Python definition is _py_getitem)",
    )
}

/// A method descriptor of type `tp` for the METH_FASTCALL function `f`, over a PyMethodDef that
/// lives forever (leaked: one per installed fast path).
fn fastcall_descriptor(
    py: Python<'_>,
    tp: *mut ffi::PyTypeObject,
    name: &'static std::ffi::CStr,
    f: ffi::PyCFunctionFast,
    doc: &'static std::ffi::CStr,
) -> PyResult<PyObject> {
    let def = Box::leak(Box::new(ffi::PyMethodDef {
        ml_name: name.as_ptr(),
        ml_meth: ffi::PyMethodDefPointer { PyCFunctionFast: f },
        ml_flags: ffi::METH_FASTCALL,
        ml_doc: doc.as_ptr(),
    }));
    // SAFETY: `tp` is a live type object and `def` is never freed
    unsafe { Ok(Bound::from_owned_ptr_or_err(py, ffi::PyDescr_NewMethod(tp, def))?.unbind()) }
}

/// `get()` / `set(tuple)` of a live vector view onto a body's field in the scene.
#[pyclass(module = "yade._ryade")]
struct FieldAccess {
    sim: Py<Sim>,
    bid: usize,
    field: VecField,
}

#[pymethods]
impl FieldAccess {
    /// `acc()` returns the field as a 3-tuple; `acc(t)` stores the 3-tuple `t`.
    #[pyo3(signature = (*args))]
    fn __call__(&self, py: Python<'_>, args: &Bound<'_, PyTuple>) -> PyResult<Option<V3>> {
        match args.len() {
            0 => Ok(Some(
                self.sim.bind(py).borrow().vec3_of(self.bid, self.field)?,
            )),
            1 => {
                let t: V3 = args.get_item(0)?.extract()?;
                self.sim
                    .bind(py)
                    .borrow_mut()
                    .set_vec3_of(self.bid, self.field, t)?;
                Ok(None)
            }
            n => Err(PyTypeError::new_err(format!(
                "a vector view takes 0 (get) or 1 (set) arguments, got {}",
                n
            ))),
        }
    }
}

// ---- O.forces.f / O.forces.t in C

/// `O.forces.f(id, sync=False)` (TORQUE false) or `O.forces.t(id, sync=False)`, bound to the `Sim`:
/// for one exact non-negative int the Vector3 is built here; any other call (keywords, other types,
/// errors) is `Sim.force_vec` / `Sim.torque_vec` with the same arguments.
///
/// # Safety
/// Called by CPython as a METH_FASTCALL | METH_KEYWORDS function whose self is a `Sim`, GIL held.
unsafe extern "C" fn sim_force<const TORQUE: bool>(
    slf: *mut ffi::PyObject,
    args: *const *mut ffi::PyObject,
    nargs: ffi::Py_ssize_t,
    kwnames: *mut ffi::PyObject,
) -> *mut ffi::PyObject {
    let py = Python::assume_gil_acquired();
    if nargs == 1 && kwnames.is_null() && ffi::PyLong_CheckExact(*args) != 0 {
        let id = ffi::PyLong_AsSsize_t(*args);
        if id >= 0 {
            let sim = Bound::from_borrowed_ptr(py, slf).downcast_into_unchecked::<Sim>();
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(
                || -> PyResult<Bound<'_, PyAny>> {
                    let s = sim.try_borrow()?;
                    let v = if TORQUE {
                        s.torque(id as usize)?
                    } else {
                        s.force(id as usize)?
                    };
                    s.vector3_type()?.plain(py, v)
                },
            ));
            return match r {
                Ok(Ok(v)) => v.into_ptr(),
                Ok(Err(e)) => {
                    e.restore(py);
                    std::ptr::null_mut()
                }
                Err(_) => {
                    PyRuntimeError::new_err("internal: panic in O.forces").restore(py);
                    std::ptr::null_mut()
                }
            };
        }
        ffi::PyErr_Clear(); // -1 for an overflow: the method below raises the error
    }
    let name = if TORQUE { c"torque_vec" } else { c"force_vec" };
    let f = ffi::PyObject_GetAttrString(slf, name.as_ptr());
    call_fastcall(f, std::ptr::null_mut(), args as *mut _, nargs, kwnames)
}

/// `_forces_accessor(sim, torque)`: `sim_force` bound to `sim`, for `O.forces.f` (`O.forces.t` when
/// `torque`).
#[pyfunction]
fn _forces_accessor(py: Python<'_>, sim: &Bound<'_, Sim>, torque: bool) -> PyResult<PyObject> {
    let (name, meth): (&'static std::ffi::CStr, ffi::PyCFunctionFastWithKeywords) = if torque {
        (c"t", sim_force::<true>)
    } else {
        (c"f", sim_force::<false>)
    };
    let def = Box::leak(Box::new(ffi::PyMethodDef {
        ml_name: name.as_ptr(),
        ml_meth: ffi::PyMethodDefPointer {
            PyCFunctionFastWithKeywords: meth,
        },
        ml_flags: ffi::METH_FASTCALL | ffi::METH_KEYWORDS,
        ml_doc: c"O.forces.f(id, sync=False) / O.forces.t(id, sync=False): a new Vector3".as_ptr(),
    }));
    // SAFETY: a builtin function bound to `sim` over a PyMethodDef that lives forever
    unsafe {
        Ok(Bound::from_owned_ptr_or_err(
            py,
            ffi::PyCFunction_NewEx(def, sim.as_ptr(), std::ptr::null_mut()),
        )?
        .unbind())
    }
}

// ---- State.__setattr__ in C

/// What `state_setattr` compares with: the interned names of the vector fields it stores directly (in
/// `FAST_FIELDS` order) and the Vector3 class with its slot offsets (None: never direct).
struct StateSetattr {
    names: [Py<PyString>; 4],
    vector3: Option<(Py<PyType>, [isize; 3])>,
}

const FAST_FIELDS: [(&str, VecField); 4] = [
    ("pos", VecField::Pos),
    ("vel", VecField::Vel),
    ("angVel", VecField::AngVel),
    ("inertia", VecField::Inertia),
];

/// Set once by `_state_setattr` (a second call replaces it; the old one is leaked), read with the GIL.
static STATE_SETATTR: std::sync::atomic::AtomicPtr<StateSetattr> =
    std::sync::atomic::AtomicPtr::new(std::ptr::null_mut());

/// The 3 coefficients of `value` if it is a plain (`_g is None`) Vector3 holding a list of 3 floats.
///
/// # Safety
/// `value` is an instance of the Vector3 class whose slots lie at `offs`; GIL held.
unsafe fn plain_vector3_floats(value: *mut ffi::PyObject, offs: &[isize; 3]) -> Option<V3> {
    if slot_ptr(value, offs[G]) != ffi::Py_None() {
        return None;
    }
    let v = slot_ptr(value, offs[V]);
    if v.is_null() || ffi::PyList_CheckExact(v) == 0 || ffi::PyList_Size(v) != 3 {
        return None;
    }
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let x = ffi::PyList_GetItem(v, k as ffi::Py_ssize_t);
        // Vector3 keeps floats (its constructors convert); anything else takes the generic path
        if ffi::PyFloat_CheckExact(x) == 0 {
            return None;
        }
        *o = ffi::PyFloat_AsDouble(x);
    }
    Some((out[0], out[1], out[2]))
}

/// Store `v` into field `f` of the body a bound state belongs to; false for an unbound state.
fn state_store(st: &Bound<'_, StateBase>, f: VecField, v: V3) -> PyResult<bool> {
    let b = st.try_borrow()?;
    match &b.sim {
        Some(sim) => {
            sim.bind(st.py())
                .try_borrow_mut()?
                .set_vec3_of(b.bid, f, v)?;
            Ok(true)
        }
        None => Ok(false),
    }
}

/// `State.__setattr__(self, name, value)`: a plain Vector3 (of floats) into pos/vel/angVel/inertia of a
/// bound state goes straight into the scene, the effect of `Serializable._assign` (convert, store,
/// `_changed`; the bound state reads these from the scene, so no copy is stored); everything else is
/// `type(self)._slow_setattr(self, name, value)`, the generic path.
///
/// # Safety
/// Called by CPython as a METH_FASTCALL method of `StateBase` (`slf` is a StateBase instance, checked
/// by the method descriptor), GIL held.
unsafe extern "C" fn state_setattr(
    slf: *mut ffi::PyObject,
    args: *mut *mut ffi::PyObject,
    nargs: ffi::Py_ssize_t,
) -> *mut ffi::PyObject {
    let py = Python::assume_gil_acquired();
    let fast = STATE_SETATTR.load(std::sync::atomic::Ordering::Acquire);
    if nargs == 2 && !fast.is_null() {
        if let Some((tp, offs)) = &(*fast).vector3 {
            let (name, value) = (*args, *args.offset(1));
            // attribute names reach tp_setattro interned (PyObject_SetAttr interns them)
            if ffi::Py_TYPE(value) == tp.as_ptr() as *mut ffi::PyTypeObject {
                if let Some(k) = (*fast).names.iter().position(|n| n.as_ptr() == name) {
                    if let Some(v) = plain_vector3_floats(value, offs) {
                        let st = Bound::from_borrowed_ptr(py, slf)
                            .downcast_into_unchecked::<StateBase>();
                        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                            state_store(&st, FAST_FIELDS[k].1, v)
                        }));
                        match r {
                            Ok(Ok(true)) => return py.None().into_ptr(),
                            Ok(Ok(false)) => {}
                            Ok(Err(e)) => {
                                e.restore(py);
                                return std::ptr::null_mut();
                            }
                            Err(_) => {
                                PyRuntimeError::new_err("internal: panic in State.__setattr__")
                                    .restore(py);
                                return std::ptr::null_mut();
                            }
                        }
                    }
                }
            }
        }
    }
    // the generic path: type(slf)._slow_setattr(slf, *args)
    let f = ffi::PyObject_GetAttrString(
        ffi::Py_TYPE(slf) as *mut ffi::PyObject,
        c"_slow_setattr".as_ptr(),
    );
    call_fastcall(f, slf, args, nargs, std::ptr::null_mut())
}

/// `_state_setattr(Vector3)`: the method descriptor of `StateBase` calling `state_setattr`, for
/// `State.__setattr__` (`State._slow_setattr` must be the generic one); plain values of `Vector3`
/// are stored directly when its slots can be located.
#[pyfunction]
fn _state_setattr(py: Python<'_>, vector3: &Bound<'_, PyType>) -> PyResult<PyObject> {
    let names = FAST_FIELDS.map(|(n, _)| PyString::intern(py, n).unbind());
    let vector3 = Vec3Type::new(vector3)?
        .slots
        .map(|o| (vector3.clone().unbind(), o));
    STATE_SETATTR.store(
        Box::into_raw(Box::new(StateSetattr { names, vector3 })),
        std::sync::atomic::Ordering::Release,
    );
    fastcall_descriptor(
        py,
        py.get_type::<StateBase>().as_type_ptr(),
        c"__setattr__",
        state_setattr,
        c"State.__setattr__ (yade._ryade.state_setattr; the generic path is _slow_setattr)",
    )
}

/// Base class of `yade._core.Omega` (`O`): `O.iter` and `O.time`, read every step by controllers, are
/// read here from the scene without a Python frame.
#[pyclass(subclass, module = "yade._ryade")]
struct OmegaBase {
    sim: Option<Py<Sim>>,
}

impl OmegaBase {
    fn sim<'py>(&self, py: Python<'py>) -> PyResult<PyRef<'py, Sim>> {
        match &self.sim {
            Some(s) => Ok(s.bind(py).borrow()),
            None => Err(PyRuntimeError::new_err(
                "internal: Omega._rs_set_sim was not called",
            )),
        }
    }
}

#[pymethods]
impl OmegaBase {
    #[new]
    #[pyo3(signature = (*_args, **_kw))]
    fn new(_args: &Bound<'_, PyTuple>, _kw: Option<&Bound<'_, PyDict>>) -> Self {
        OmegaBase { sim: None }
    }
    fn _rs_set_sim(&mut self, sim: Py<Sim>) {
        self.sim = Some(sim);
    }
    /// `O.iter`: the number of steps done.
    #[getter]
    fn iter(&self, py: Python<'_>) -> PyResult<i64> {
        Ok(self.sim(py)?.scene.iter)
    }
    /// `O.time`: the simulated time.
    #[getter]
    fn time(&self, py: Python<'_>) -> PyResult<f64> {
        Ok(self.sim(py)?.scene.time)
    }
}

/// Base class of `yade._core.State` holding what its hot paths need without Python code: the scene
/// (`Sim`) and the body id once the body is in `O.bodies`. `State.__setattr__` is `state_setattr`
/// (a Vector3 stored into pos/vel/angVel/inertia of a bound state goes straight to the scene; every
/// other assignment is `State._slow_setattr`, the generic path); `pos`, `vel`, `angVel` are read here.
#[pyclass(subclass, module = "yade._ryade")]
struct StateBase {
    sim: Option<Py<Sim>>,
    bid: usize,
}

impl StateBase {
    fn read(slf: &Bound<'_, Self>, field: VecField, name: &str) -> PyResult<PyObject> {
        let py = slf.py();
        let (sim, bid) = {
            let b = slf.borrow();
            match &b.sim {
                Some(s) => (s.clone_ref(py), b.bid),
                None => return Ok(slf.call_method1(intern!(py, "_read"), (name,))?.unbind()),
            }
        };
        let s = sim.bind(py).borrow();
        let tp = s.vector3_type()?;
        if let VecField::Pos = field {
            // YADE quirk kept on purpose: pos and ori are computed properties (se3), so
            // `b.state.pos[1] = 3` changes a temporary copy and leaves the body where it was
            return Ok(tp.plain(py, s.vec3_of(bid, field)?)?.unbind());
        }
        s.check_id(bid)?;
        let sim2 = sim.clone_ref(py);
        Ok(tp
            .view(
                py,
                FieldAccess {
                    sim: sim2,
                    bid,
                    field,
                },
            )?
            .unbind())
    }
}

#[pymethods]
impl StateBase {
    #[new]
    #[pyo3(signature = (*_args, **_kw))]
    fn new(_args: &Bound<'_, PyTuple>, _kw: Option<&Bound<'_, PyDict>>) -> Self {
        StateBase { sim: None, bid: 0 }
    }
    /// The state now belongs to body `bid` of `sim`.
    fn _rs_bind(&mut self, sim: Py<Sim>, bid: usize) {
        self.sim = Some(sim);
        self.bid = bid;
    }
    /// `State.pos`: a copy (YADE computes it from se3).
    #[getter]
    fn pos(slf: &Bound<'_, Self>) -> PyResult<PyObject> {
        Self::read(slf, VecField::Pos, "pos")
    }
    /// `State.vel`: a live view (`b.state.vel[2] = 0.1` moves the body).
    #[getter]
    fn vel(slf: &Bound<'_, Self>) -> PyResult<PyObject> {
        Self::read(slf, VecField::Vel, "vel")
    }
    /// `State.angVel`: a live view.
    #[getter(angVel)]
    fn ang_vel(slf: &Bound<'_, Self>) -> PyResult<PyObject> {
        Self::read(slf, VecField::AngVel, "angVel")
    }
}

impl Sim {
    fn check_id(&self, id: usize) -> PyResult<()> {
        if id >= self.scene.bodies.len() {
            return Err(PyIndexError::new_err(format!(
                "body id {} out of range (there are {} bodies)",
                id,
                self.scene.bodies.len()
            )));
        }
        Ok(())
    }

    fn vec3_of(&self, id: usize, f: VecField) -> PyResult<V3> {
        self.check_id(id)?;
        let b = &self.scene.bodies;
        Ok(v3(match f {
            VecField::Pos => &b.pos[id],
            VecField::Vel => &b.vel[id],
            VecField::AngVel => &b.ang_vel[id],
            VecField::Inertia => &b.inertia[id],
            VecField::AngMom => &b.ang_mom[id],
        }))
    }

    fn set_vec3_of(&mut self, id: usize, f: VecField, v: V3) -> PyResult<()> {
        self.check_id(id)?;
        let b = &mut self.scene.bodies;
        *(match f {
            VecField::Pos => &mut b.pos[id],
            VecField::Vel => &mut b.vel[id],
            VecField::AngVel => &mut b.ang_vel[id],
            VecField::Inertia => &mut b.inertia[id],
            VecField::AngMom => &mut b.ang_mom[id],
        }) = vec(v);
        Ok(())
    }

    fn vector3_type(&self) -> PyResult<&Vec3Type> {
        self.vector3
            .as_ref()
            .ok_or_else(|| PyRuntimeError::new_err("internal: Sim._set_vector3 was not called"))
    }

    fn intr_index(&self, a: u32, b: u32) -> PyResult<usize> {
        self.scene
            .interactions
            .find(a, b)
            .ok_or_else(|| PyKeyError::new_err(format!("no interaction between #{} and #{}", a, b)))
    }
}

/// The thread count `compat run -jN` passes in `RYADE_THREADS` (1 when unset or not a count >= 1).
/// `RYADE_PAR_MIN_SLOTS`: overrides `Scene::par_min_slots` (tests force the threaded pre-pass on
/// small scenes with 0).
fn env_par_min_slots() -> usize {
    std::env::var("RYADE_PAR_MIN_SLOTS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .unwrap_or(ryade::scene::PAR_MIN_SLOTS)
}

fn env_threads() -> usize {
    std::env::var("RYADE_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .filter(|&n| n >= 1)
        .unwrap_or(1)
}

#[pymethods]
impl Sim {
    #[new]
    fn new() -> Self {
        Sim {
            scene: Scene {
                threads: env_threads(),
                par_min_slots: env_par_min_slots(),
                ..Scene::default()
            },
            saved: HashMap::new(),
            cursor: None,
            vector3: None,
        }
    }
    /// `O.numThreads`: the YADE-order path's thread count (`compat run -jN`; same bits for any).
    #[getter]
    fn threads(&self) -> usize {
        self.scene.threads
    }
    /// The `Vector3` class the fast paths (`force_vec`, `StateBase`) build their values of.
    fn _set_vector3(&mut self, tp: &Bound<'_, PyType>) -> PyResult<()> {
        self.vector3 = Some(Vec3Type::new(tp)?);
        Ok(())
    }
    /// Whether the slots of the Vector3 class were found (the fast paths then skip getattr/setattr).
    fn _vector3_slots_found(&self) -> bool {
        self.vector3.as_ref().is_some_and(|t| t.slots.is_some())
    }

    /// `O.reset()`: empty scene, no engines, dt = 1e-8.
    fn reset(&mut self) {
        self.scene = Scene {
            threads: self.scene.threads,
            par_min_slots: self.scene.par_min_slots,
            timing_enabled: self.scene.timing_enabled,
            ..Scene::default()
        };
        self.cursor = None;
    }

    // ---- time ----
    #[getter]
    fn dt(&self) -> f64 {
        self.scene.dt
    }
    #[setter]
    fn set_dt(&mut self, dt: f64) {
        self.scene.dt = dt;
    }
    #[getter]
    fn iter(&self) -> i64 {
        self.scene.iter
    }
    #[setter]
    fn set_iter(&mut self, i: i64) {
        self.scene.iter = i;
    }
    #[getter]
    fn time(&self) -> f64 {
        self.scene.time
    }
    #[setter]
    fn set_time(&mut self, t: f64) {
        self.scene.time = t;
    }
    #[getter]
    fn track_energy(&self) -> bool {
        self.scene.track_energy
    }
    #[setter]
    fn set_track_energy(&mut self, on: bool) {
        self.scene.track_energy = on;
    }
    /// `O.energy.items()`: (name, value) in name order (YADE's EnergyTracker; filled while
    /// `O.trackEnergy`, readable at any time).
    fn energy_items(&self) -> Vec<(String, f64)> {
        self.scene.energy.items()
    }
    /// `O.energy.total()`: the values summed in creation order.
    fn energy_total(&self) -> f64 {
        self.scene.energy.total()
    }
    /// `O.energy[name]`; None for an unknown name.
    fn energy_get(&self, name: &str) -> Option<f64> {
        self.scene.energy.get_item(name)
    }
    /// `O.energy[name] = value` (a new name is not reset every step).
    fn energy_set(&mut self, name: &str, value: f64) {
        self.scene.energy.set_item(name, value)
    }
    /// `O.energy.clear()`.
    fn energy_clear(&mut self) {
        self.scene.energy.clear()
    }

    // ---- materials ----
    /// Add a material given as the scene-file JSON object; returns its internal index.
    fn add_material(&mut self, json: &str) -> PyResult<usize> {
        let v: Value = serde_json::from_str(json).map_err(err)?;
        scene_json::material(&v, &mut self.scene.materials).map_err(err)
    }
    /// A material's friction angle as the core has it (engines such as TriaxialCompressionEngine
    /// change it).
    fn material_friction_angle(&self, idx: usize) -> PyResult<f64> {
        self.scene
            .materials
            .get(idx)
            .map(|m| m.friction_angle)
            .ok_or_else(|| PyIndexError::new_err(format!("no material #{}", idx)))
    }
    /// `Shop::setContactFriction(deg·π/180)` (`skip_clumps`) or ThreeDTriaxialEngine's variant.
    fn set_contact_friction_degrees(&mut self, degrees: f64, skip_clumps: bool) {
        ryade::triax_compression::set_contact_friction(
            &mut self.scene,
            degrees * std::f64::consts::PI / 180.0,
            skip_clumps,
        );
    }
    fn material_set(&mut self, idx: usize, key: &str, value: f64) -> PyResult<()> {
        let m = self
            .scene
            .materials
            .get_mut(idx)
            .ok_or_else(|| PyIndexError::new_err(format!("no material #{}", idx)))?;
        match key {
            "young" => m.young = value,
            "poisson" => m.poisson = value,
            "frictionAngle" => m.friction_angle = value,
            "density" => m.density = value,
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "FrictMat has no attribute '{}' in ryade",
                    key
                )))
            }
        }
        Ok(())
    }
    fn material_index_of_body(&self, id: usize) -> PyResult<usize> {
        self.check_id(id)?;
        Ok(self.scene.bodies.material[id])
    }

    // ---- bodies ----
    /// Add a body given as the scene-file JSON object; returns its id.
    fn add_body(&mut self, json: &str) -> PyResult<usize> {
        let v: Value = serde_json::from_str(json).map_err(err)?;
        let spec = scene_json::body(&v, &mut self.scene.materials).map_err(err)?;
        let id = self.scene.bodies.push(spec);
        self.scene.forces.resize(self.scene.bodies.len());
        Ok(id)
    }
    /// `O.bodies.clump(ids, discretization)`: a clump body appended after `ids` (Clump::add +
    /// Clump::updateProperties); returns its id.
    fn make_clump(&mut self, ids: Vec<usize>, discretization: u32) -> PyResult<usize> {
        let cid = ryade::clump::make_clump(
            &mut self.scene.bodies,
            &self.scene.materials,
            &ids,
            discretization,
        )
        // YADE raises ValueError (std::invalid_argument) for a body listed twice
        .map_err(|e| {
            if e.contains("already part of this clump") {
                PyValueError::new_err(e)
            } else {
                PyRuntimeError::new_err(e)
            }
        })?;
        self.scene.forces.resize(self.scene.bodies.len());
        Ok(cid)
    }
    fn n_bodies(&self) -> usize {
        self.scene.bodies.len()
    }
    fn get_vec3(&self, id: usize, field: &str) -> PyResult<V3> {
        self.check_id(id)?;
        self.vec3_of(
            id,
            VecField::parse(field).ok_or_else(|| VecField::no_such(field))?,
        )
    }
    fn set_vec3(&mut self, id: usize, field: &str, v: V3) -> PyResult<()> {
        self.check_id(id)?;
        self.set_vec3_of(
            id,
            VecField::parse(field).ok_or_else(|| VecField::no_such(field))?,
            v,
        )
    }
    /// Orientation as (w, x, y, z).
    fn get_ori(&self, id: usize) -> PyResult<(f64, f64, f64, f64)> {
        self.check_id(id)?;
        let q = self.scene.bodies.ori[id];
        Ok((q.w, q.x, q.y, q.z))
    }
    fn set_ori(&mut self, id: usize, q: (f64, f64, f64, f64)) -> PyResult<()> {
        self.check_id(id)?;
        self.scene.bodies.ori[id] = Quat::new(q.0, q.1, q.2, q.3);
        Ok(())
    }
    fn get_scalar(&self, id: usize, field: &str) -> PyResult<f64> {
        self.check_id(id)?;
        let b = &self.scene.bodies;
        Ok(match field {
            "mass" => b.mass[id],
            "radius" => b.shape[id].sphere_radius().ok_or_else(|| {
                PyKeyError::new_err(format!(
                    "body #{} is a {}, not a Sphere",
                    id,
                    b.shape[id].class_name()
                ))
            })?,
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "no scalar attribute '{}' in ryade",
                    field
                )))
            }
        })
    }
    fn set_scalar(&mut self, id: usize, field: &str, v: f64) -> PyResult<()> {
        self.check_id(id)?;
        let b = &mut self.scene.bodies;
        match field {
            "mass" => b.mass[id] = v,
            "radius" => match &mut b.shape[id] {
                Shape::Sphere { radius } => *radius = v,
                s => {
                    return Err(PyKeyError::new_err(format!(
                        "body #{} is a {}, not a Sphere",
                        id,
                        s.class_name()
                    )))
                }
            },
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "no scalar attribute '{}' in ryade",
                    field
                )))
            }
        }
        Ok(())
    }
    fn get_int(&self, id: usize, field: &str) -> PyResult<i64> {
        self.check_id(id)?;
        let b = &self.scene.bodies;
        Ok(match field {
            "blockedDOFs" => b.blocked[id] as i64,
            "mask" => b.mask[id] as i64,
            "isDamped" => b.is_damped[id] as i64,
            "bounded" => b.bounded[id] as i64,
            "clumpId" => b.clump_id[id].map_or(-1, |c| c as i64),
            "aspherical" => b.aspherical[id] as i64,
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "no integer attribute '{}' in ryade",
                    field
                )))
            }
        })
    }
    fn set_int(&mut self, id: usize, field: &str, v: i64) -> PyResult<()> {
        self.check_id(id)?;
        let b = &mut self.scene.bodies;
        match field {
            "blockedDOFs" => {
                if !(0..64).contains(&v) {
                    return Err(PyValueError::new_err("blockedDOFs bits must be in 0..63"));
                }
                b.blocked[id] = v as u8
            }
            "mask" => b.mask[id] = v as i32,
            "isDamped" => b.is_damped[id] = v != 0,
            "bounded" => b.bounded[id] = v != 0,
            "aspherical" => b.aspherical[id] = v != 0,
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "no integer attribute '{}' in ryade",
                    field
                )))
            }
        }
        Ok(())
    }
    /// The shape as the scene-file JSON object.
    fn shape_json(&self, id: usize) -> PyResult<String> {
        self.check_id(id)?;
        let v = scene_json::to_value(&self.scene, 0);
        Ok(v["bodies"][id]["shape"].to_string())
    }

    // ---- periodic cell ----
    /// Set the cell (rows of hSize) or None for an aperiodic scene.
    #[pyo3(signature = (hsize=None))]
    /// `O.cell.hSize = h` (`Cell::setHSize`: trsf and velGrad kept, cached values refreshed), a new
    /// cell for a scene that was not periodic, or no cell (`None`).
    fn set_cell(&mut self, hsize: Option<[[f64; 3]; 3]>) -> PyResult<()> {
        let Some(h) = hsize else {
            self.scene.cell = None;
            return Ok(());
        };
        let h = ryade::math::Mat3::from_fn(|i, j| h[i][j]);
        match self.scene.cell.as_mut() {
            Some(c) => {
                c.hsize = h;
                c.integrate_and_update(0.0).map_err(err)?;
            }
            None => self.scene.cell = Some(ryade::cell::Cell::new(h).map_err(err)?),
        }
        Ok(())
    }
    /// A matrix of the cell by YADE's attribute name: trsf, velGrad, nextVelGrad, prevVelGrad.
    fn cell_matrix(&self, name: &str) -> PyResult<[[f64; 3]; 3]> {
        let c = self
            .scene
            .cell
            .as_ref()
            .ok_or_else(|| PyRuntimeError::new_err("the scene is not periodic"))?;
        let m = match name {
            "trsf" => c.trsf,
            "velGrad" => c.vel_grad,
            "nextVelGrad" => c.next_vel_grad,
            "prevVelGrad" => c.prev_vel_grad,
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "Cell has no matrix '{}' in ryade",
                    name
                )))
            }
        };
        Ok(rows3(&m))
    }
    /// Assign a cell matrix as YADE does: `velGrad` goes to nextVelGrad (NewtonIntegrator applies it
    /// after the interaction loop, `Cell::setVelGrad`), `nextVelGrad` directly, `trsf` with postLoad.
    fn set_cell_matrix(&mut self, name: &str, m: [[f64; 3]; 3]) -> PyResult<()> {
        let c = self
            .scene
            .cell
            .as_mut()
            .ok_or_else(|| PyRuntimeError::new_err("the scene is not periodic"))?;
        let m = ryade::math::Mat3::from_fn(|i, j| m[i][j]);
        match name {
            "velGrad" => {
                c.next_vel_grad = m;
                c.vel_grad_changed = true;
            }
            "nextVelGrad" => c.next_vel_grad = m,
            "trsf" => {
                c.trsf = m;
                c.integrate_and_update(0.0).map_err(err)?;
            }
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "Cell.{} cannot be assigned in ryade",
                    name
                )))
            }
        }
        Ok(())
    }
    /// `Cell.velGradChanged`.
    fn cell_vel_grad_changed(&self) -> Option<bool> {
        self.scene.cell.as_ref().map(|c| c.vel_grad_changed)
    }
    /// `Cell.homoDeform` (read / write).
    fn cell_homo_deform(&self) -> Option<i32> {
        self.scene.cell.as_ref().map(|c| c.homo_deform)
    }
    fn set_cell_homo_deform(&mut self, h: i32) -> PyResult<()> {
        let c = self
            .scene
            .cell
            .as_mut()
            .ok_or_else(|| PyRuntimeError::new_err("the scene is not periodic"))?;
        c.homo_deform = h;
        Ok(())
    }
    fn get_cell(&self) -> Option<[[f64; 3]; 3]> {
        self.scene.cell.as_ref().map(|c| rows3(&c.hsize))
    }
    fn cell_size(&self) -> Option<V3> {
        self.scene.cell.as_ref().map(|c| v3(&c.size()))
    }
    fn cell_volume(&self) -> Option<f64> {
        self.scene.cell.as_ref().map(|c| c.volume())
    }
    fn cell_wrap(&self, p: V3) -> PyResult<V3> {
        let c = self
            .scene
            .cell
            .as_ref()
            .ok_or_else(|| PyRuntimeError::new_err("the scene is not periodic"))?;
        Ok(v3(&c.wrap_pt(&vec(p))))
    }

    // ---- engines ----
    /// Replace the engine list (JSON array of scene-file engine objects; Python engines are
    /// `{"class": "External", "id": k}`). `reuse[k]`, when given, is the slot in the current list of
    /// the same engine object: that engine keeps its state (a collider its sorted bounds and
    /// stride, Newton its maxima, a servo its integral), as the object does in YADE.
    #[pyo3(signature = (json, reuse=None))]
    fn set_engines(&mut self, json: &str, reuse: Option<Vec<Option<usize>>>) -> PyResult<()> {
        let v: Value = serde_json::from_str(json).map_err(err)?;
        let arr = v
            .as_array()
            .ok_or_else(|| PyValueError::new_err("engines must be a list"))?;
        let mut engines: Vec<Engine> = arr
            .iter()
            .map(scene_json::engine)
            .collect::<Result<_, _>>()
            .map_err(err)?;
        let mut old = std::mem::take(&mut self.scene.engines);
        for (e, j) in engines.iter_mut().zip(reuse.unwrap_or_default()) {
            match j.and_then(|j| old.get_mut(j)) {
                Some(o) if o.class_name() == e.class_name() => {
                    *e = std::mem::replace(o, Engine::External(u32::MAX))
                }
                _ => {}
            }
        }
        self.scene.engine_dead = vec![false; engines.len()];
        self.scene.engines = engines;
        // the Python side has harvested the old list's timings into its engine objects
        self.scene.timing.clear();
        Ok(())
    }
    /// `O.timingEnabled` (YADE's `TimingInfo::enabled`, kept across `O.reset()` as YADE's static is).
    #[getter]
    fn timing_enabled(&self) -> bool {
        self.scene.timing_enabled
    }
    #[setter]
    fn set_timing_enabled(&mut self, on: bool) {
        self.scene.timing_enabled = on;
    }
    /// (nanoseconds, runs) of engine slot `k` since the engine list was set or the slot reset.
    fn engine_timing(&self, k: usize) -> (u64, u64) {
        self.scene
            .timing
            .get(k)
            .map_or((0, 0), |t| (t.nsec, t.count))
    }
    /// YADE's `timingDeltas` of engine slot `k`: (checkpoint, ns, count).
    fn engine_timing_deltas(&self, k: usize) -> Vec<(String, u64, u64)> {
        self.scene.timing.get(k).map_or(Vec::new(), |t| {
            t.deltas
                .iter()
                .map(|&(n, ns, c)| (n.to_string(), ns, c))
                .collect()
        })
    }
    fn engine_timing_reset(&mut self, k: usize) {
        if let Some(t) = self.scene.timing.get_mut(k) {
            *t = Default::default();
        }
    }
    fn set_engine_dead(&mut self, idx: usize, dead: bool) -> PyResult<()> {
        if idx >= self.scene.engines.len() {
            return Err(PyIndexError::new_err(format!("no engine #{}", idx)));
        }
        self.scene
            .engine_dead
            .resize(self.scene.engines.len(), false);
        self.scene.engine_dead[idx] = dead;
        Ok(())
    }
    /// Change one attribute of a built-in engine (value as JSON) without resetting its state.
    fn engine_set(&mut self, idx: usize, key: &str, json: &str) -> PyResult<()> {
        let v: Value = serde_json::from_str(json).map_err(err)?;
        let e = self
            .scene
            .engines
            .get_mut(idx)
            .ok_or_else(|| PyIndexError::new_err(format!("no engine #{}", idx)))?;
        engine_set_attr(e, key, &v)
    }
    /// `TriaxialStressController::computeStressStrain` of the controller at slot `idx` (what
    /// TriaxialStateRecorder calls off the controller's period).
    fn triax_compute_stress_strain(&mut self, idx: usize) -> PyResult<()> {
        let e = self
            .scene
            .engines
            .get_mut(idx)
            .ok_or_else(|| PyIndexError::new_err(format!("no engine #{}", idx)))?;
        let Engine::TriaxialStress(t) = e else {
            return Err(PyValueError::new_err(format!(
                "engine #{} is not a TriaxialStressController",
                idx
            )));
        };
        let mut t = t.clone();
        let r = t.compute_stress_strain(&self.scene);
        self.scene.engines[idx] = Engine::TriaxialStress(t);
        r.map_err(PyRuntimeError::new_err)
    }
    /// `TriaxialStressController.strainRate()` (JSON vector).
    fn triax_strain_rate(&self, idx: usize) -> PyResult<String> {
        match self.scene.engines.get(idx) {
            Some(Engine::TriaxialStress(t)) => Ok(v3json(&t.strain_rate(&self.scene)).to_string()),
            _ => Err(PyValueError::new_err(format!(
                "engine #{} is not a TriaxialStressController",
                idx
            ))),
        }
    }
    /// Read an attribute of a built-in engine (JSON).
    fn engine_get(&self, idx: usize, key: &str) -> PyResult<String> {
        let e = self
            .scene
            .engines
            .get(idx)
            .ok_or_else(|| PyIndexError::new_err(format!("no engine #{}", idx)))?;
        Ok(engine_get_attr(e, key)?.to_string())
    }

    /// `RyadePistonController.boxPorosity(...)`: the study script's box porosity of spheres `ids`
    /// as they are in the scene (`ryade::porosity::study_box_porosity`, the same bits as the script).
    #[allow(clippy::too_many_arguments)]
    fn study_box_porosity(
        &self,
        ids: Vec<i64>,
        lo: V3,
        hi: V3,
        lx: f64,
        ly: f64,
        gl_x: Vec<f64>,
        gl_w: Vec<f64>,
    ) -> PyResult<f64> {
        let b = &self.scene.bodies;
        let spheres = ids
            .iter()
            .map(|&id| {
                let r = usize::try_from(id)
                    .ok()
                    .filter(|&i| i < b.len())
                    .and_then(|i| b.shape[i].sphere_radius().map(|r| (b.pos[i], r)));
                r.ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "boxPorosity: body {} is not a sphere of this scene; pass the ids of spheres",
                        id
                    ))
                })
            })
            .collect::<PyResult<Vec<_>>>()?;
        if gl_x.len() != gl_w.len() || !(lx > 0.0 && ly > 0.0) {
            return Err(PyValueError::new_err(format!(
                "boxPorosity: need as many nodes as weights ({} and {}) and positive periods ({}, {})",
                gl_x.len(),
                gl_w.len(),
                lx,
                ly
            )));
        }
        Ok(ryade::porosity::study_box_porosity(
            &spheres,
            &vec(lo),
            &vec(hi),
            (lx, ly),
            (&gl_x, &gl_w),
        ))
    }

    /// `RyadePistonController.takeSteps()`: the `steps.csv` samples buffered by the piston engine at
    /// slot `idx` since the last call, as (iter, phase, p_kPa, pf_kPa, target_kPa, z_m, v_mps).
    #[allow(clippy::type_complexity)]
    fn piston_take_rows(
        &mut self,
        idx: usize,
    ) -> PyResult<Vec<(i64, &'static str, f64, f64, f64, f64, f64)>> {
        match self.scene.engines.get_mut(idx) {
            Some(Engine::Piston(pc)) => Ok(std::mem::take(&mut pc.rows)
                .into_iter()
                .map(|r| {
                    (
                        r.iter,
                        r.phase.name(),
                        r.p_kpa,
                        r.pf_kpa,
                        r.target_kpa,
                        r.z,
                        r.v,
                    )
                })
                .collect()),
            _ => Err(PyIndexError::new_err(format!(
                "engine #{} is not a RyadePistonController",
                idx
            ))),
        }
    }
    /// Whether an engine asked to end the run after the step just done (`RyadePistonController`);
    /// the request is cleared. The Python run loop calls it after each step.
    fn take_stop_request(&mut self) -> bool {
        std::mem::take(&mut self.scene.stop_requested)
    }

    // ---- stepping ----
    /// Run the current step until the next live Python engine, whose id is returned (with the
    /// `DONE_HOOK` bit set: the engine slot of a PeriTriaxController whose doneHook Python must run
    /// now); None when the step is complete (iter and time then advanced).
    fn advance(&mut self) -> PyResult<Option<u32>> {
        let mut k = match self.cursor {
            Some(k) => k,
            None => {
                self.scene.step_prologue().map_err(err)?;
                0
            }
        };
        while k < self.scene.engines.len() {
            if !self.scene.is_dead(k) {
                if let Engine::External(id) = self.scene.engines[k] {
                    self.cursor = Some(k + 1);
                    return Ok(Some(id));
                }
                if let Err(e) = self.scene.run_engine(k) {
                    self.cursor = None;
                    return Err(err(e));
                }
                if let Some(slot) = self.scene.done_hook_pending.take() {
                    // a PeriTriaxController's doneHook: Python runs it before the next engine
                    self.cursor = Some(k + 1);
                    return Ok(Some(ryade::scene::DONE_HOOK | slot as u32));
                }
            }
            k += 1;
        }
        self.scene.step_epilogue();
        self.cursor = None;
        Ok(None)
    }
    /// True while a step is half done (a Python engine is running).
    fn in_step(&self) -> bool {
        self.cursor.is_some()
    }
    /// Run `n` whole steps in Rust (fewer when an engine asks to stop); fails if a live Python engine
    /// is in the list.
    fn run_steps(&mut self, py: Python<'_>, n: u64) -> PyResult<()> {
        if self.cursor.is_some() {
            return Err(PyRuntimeError::new_err(
                "run_steps called in the middle of a step",
            ));
        }
        let scene = &mut self.scene;
        // an engine may end the run after a step (`RyadePistonController`: `O.stopAtIter = O.iter + 1`
        // in a PyRunner); a request left from an earlier O.step() does not count
        scene.stop_requested = false;
        // in chunks, with Python's signal check between them: Ctrl-C and SIGTERM stop a long run
        let mut left = n;
        while left > 0 {
            let k = left.min(SIGNAL_CHECK_STEPS);
            left -= k;
            let stopped = py
                .allow_threads(|| {
                    for _ in 0..k {
                        scene.step().map_err(|e| e.to_string())?;
                        if std::mem::take(&mut scene.stop_requested) {
                            return Ok(true);
                        }
                    }
                    Ok::<bool, String>(false)
                })
                .map_err(PyRuntimeError::new_err)?;
            if stopped {
                break;
            }
            py.check_signals()?;
        }
        Ok(())
    }

    /// Run `n` whole steps on the fast path (`ryade::fast`, `O.ryadeFastPath = True`): the state goes
    /// back into the scene afterwards, contacts included. Fails with the reason for scenes outside it.
    fn run_steps_fast(&mut self, py: Python<'_>, n: u64, threads: usize) -> PyResult<()> {
        if self.cursor.is_some() {
            return Err(PyRuntimeError::new_err(
                "run_steps_fast called in the middle of a step",
            ));
        }
        let scene = &mut self.scene;
        let opt = ryade::fast::FastOptions {
            threads: threads.max(1),
            ..Default::default()
        };
        let mut n = n;
        if n > 0 && ryade::fast::cohesion_now_pending(scene) {
            // a setCohesionNow acts in this iteration: that step runs on the YADE-order path (when
            // the fast path can take the rest; else nothing changes here and the caller falls back)
            py.allow_threads(|| {
                ryade::fast::FastSim::check_after_cohesion_now(scene, opt)
                    .map_err(|e| format!("O.ryadeFastPath: {}", e))?;
                scene.stop_requested = false;
                scene.step().map_err(|e| e.to_string())
            })
            .map_err(PyRuntimeError::new_err)?;
            n -= 1;
            if std::mem::take(&mut scene.stop_requested) || n == 0 {
                return Ok(());
            }
        }
        let t_setup = std::time::Instant::now();
        py.allow_threads(|| {
            ryade::fast::FastSim::from_scene(scene, opt)
                .map_err(|e| format!("O.ryadeFastPath: {}", e))
        })
        .map_err(PyRuntimeError::new_err)
        .and_then(|mut f| {
            let setup_s = t_setup.elapsed().as_secs_f64();
            // in chunks, with Python's signal check between them (the state goes back either way)
            let mut left = n;
            let mut r = Ok(());
            while left > 0 {
                let k = left.min(SIGNAL_CHECK_STEPS);
                left -= k;
                py.allow_threads(|| f.run(k));
                // an engine ended the run (the study's piston: its stops), as `run_steps` does
                if f.take_stop() {
                    break;
                }
                r = py.check_signals();
                if r.is_err() {
                    break;
                }
            }
            let t_back = std::time::Instant::now();
            py.allow_threads(|| f.write_back(scene));
            let back_s = t_back.elapsed().as_secs_f64();
            if std::env::var_os("RYADE_FAST_STATS").is_some() {
                // one line per fast run: what it held and where its time went
                let m = f.memory();
                eprintln!(
                    "[ryade] fast run to iteration {}: {} bodies, {} listed pairs, {} contacts, {} grid interactions, {} list builds; memory {:.0} B/particle, {:.0} B/listed pair, {:.0} B/contact; time: lists {:.3} s, contacts {:.3} s (grid {:.3} s), integration {:.3} s; set-up {:.3} s, state back into the scene {:.3} s",
                    f.iter,
                    f.len(),
                    f.pairs(),
                    f.active_contacts(),
                    f.grid_interactions(),
                    f.rebuilds,
                    m.per_particle,
                    m.per_pair,
                    m.per_contact,
                    f.timing.rebuild,
                    f.timing.contacts,
                    f.timing.grid,
                    f.timing.newton,
                    setup_s,
                    back_s
                );
            }
            if let Some(e) = f.take_error() {
                return Err(PyRuntimeError::new_err(format!(
                    "fast path, iteration {}: {}",
                    scene.iter, e
                )));
            }
            r
        })
    }

    // ---- forces ----
    /// `O.forces.f(id)`: the force as a new Vector3.
    #[pyo3(signature = (id, sync=false))]
    fn force_vec<'py>(
        &self,
        py: Python<'py>,
        id: usize,
        sync: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let _ = sync;
        self.vector3_type()?.plain(py, self.force(id)?)
    }
    /// `O.forces.t(id)`: the torque as a new Vector3.
    #[pyo3(signature = (id, sync=false))]
    fn torque_vec<'py>(
        &self,
        py: Python<'py>,
        id: usize,
        sync: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let _ = sync;
        self.vector3_type()?.plain(py, self.torque(id)?)
    }
    fn force(&self, id: usize) -> PyResult<V3> {
        self.check_id(id)?;
        Ok(self
            .scene
            .forces
            .ft
            .get(id)
            .map(|w| v3(&w.f))
            .unwrap_or((0.0, 0.0, 0.0)))
    }
    fn torque(&self, id: usize) -> PyResult<V3> {
        self.check_id(id)?;
        Ok(self
            .scene
            .forces
            .ft
            .get(id)
            .map(|w| v3(&w.t))
            .unwrap_or((0.0, 0.0, 0.0)))
    }
    fn add_force(&mut self, id: usize, f: V3) -> PyResult<()> {
        self.check_id(id)?;
        self.scene.forces.resize(self.scene.bodies.len());
        self.scene.forces.add_force(id, &vec(f));
        Ok(())
    }
    fn add_torque(&mut self, id: usize, t: V3) -> PyResult<()> {
        self.check_id(id)?;
        self.scene.forces.resize(self.scene.bodies.len());
        self.scene.forces.add_torque(id, &vec(t));
        Ok(())
    }
    fn set_perm_force(&mut self, id: usize, f: V3) -> PyResult<()> {
        self.check_id(id)?;
        self.scene.forces.resize(self.scene.bodies.len());
        self.scene.forces.perm_force[id] = vec(f);
        self.scene.forces.perm_used = true;
        Ok(())
    }
    fn set_perm_torque(&mut self, id: usize, t: V3) -> PyResult<()> {
        self.check_id(id)?;
        self.scene.forces.resize(self.scene.bodies.len());
        self.scene.forces.perm_torque[id] = vec(t);
        self.scene.forces.perm_used = true;
        Ok(())
    }

    // ---- interactions ----
    /// (id1, id2) of the interactions in container order, real ones only unless `only_real` is false.
    fn intr_list(&self, only_real: bool) -> Vec<(u32, u32)> {
        self.scene
            .interactions
            .list
            .iter()
            .filter(|i| !only_real || i.is_real())
            .map(|i| (i.id1, i.id2))
            .collect()
    }
    fn intr_count_real(&self) -> usize {
        self.scene.interactions.count_real()
    }
    fn intr_exists(&self, a: u32, b: u32) -> bool {
        self.scene.interactions.find(a, b).is_some()
    }
    /// One attribute of an interaction's geometry or physics, as a float or a 3-tuple.
    fn intr_get(&self, py: Python<'_>, a: u32, b: u32, field: &str) -> PyResult<PyObject> {
        let it = &self.scene.interactions.list[self.intr_index(a, b)?];
        let no = |what: &str| {
            PyKeyError::new_err(format!(
                "interaction #{}+#{} has no {} (it is not real)",
                a, b, what
            ))
        };
        Ok(match field {
            "id1" => it.id1.into_pyobject(py)?.into_any().unbind(),
            "id2" => it.id2.into_pyobject(py)?.into_any().unbind(),
            "isReal" => it
                .is_real()
                .into_pyobject(py)?
                .to_owned()
                .into_any()
                .unbind(),
            "iterMadeReal" => it.iter_made_real.into_pyobject(py)?.into_any().unbind(),
            "iterBorn" => it.iter_born.into_pyobject(py)?.into_any().unbind(),
            "cellDist" => (it.cell_dist[0], it.cell_dist[1], it.cell_dist[2])
                .into_pyobject(py)?
                .into_any()
                .unbind(),
            "normal" | "penetrationDepth" | "contactPoint" | "shearInc" | "refR1" | "refR2" => {
                let g = it.geom.as_ref().ok_or_else(|| no("geom"))?;
                match field {
                    "normal" => v3(&g.normal).into_pyobject(py)?.into_any().unbind(),
                    "penetrationDepth" => g.pen.into_pyobject(py)?.into_any().unbind(),
                    "contactPoint" => v3(&g.contact_point).into_pyobject(py)?.into_any().unbind(),
                    "shearInc" => v3(&g.shear_inc).into_pyobject(py)?.into_any().unbind(),
                    "refR1" => g.radius1.into_pyobject(py)?.into_any().unbind(),
                    _ => g.radius2.into_pyobject(py)?.into_any().unbind(),
                }
            }
            "normalForce" | "shearForce" | "kn" | "ks" | "tangensOfFrictionAngle" => {
                let p = it.phys.as_ref().ok_or_else(|| no("phys"))?;
                match field {
                    "normalForce" => v3(&p.normal_force).into_pyobject(py)?.into_any().unbind(),
                    "shearForce" => v3(&p.shear_force).into_pyobject(py)?.into_any().unbind(),
                    "kn" => p.kn.into_pyobject(py)?.into_any().unbind(),
                    "ks" => p.ks.into_pyobject(py)?.into_any().unbind(),
                    _ => p.tan_phi.into_pyobject(py)?.into_any().unbind(),
                }
            }
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "interactions have no attribute '{}' in ryade",
                    field
                )))
            }
        })
    }
    /// Cohesive / 6-D / grid attributes (None when the interaction has no such data).
    fn intr_get_ext(&self, py: Python<'_>, a: u32, b: u32, field: &str) -> PyResult<PyObject> {
        let it = &self.scene.interactions.list[self.intr_index(a, b)?];
        let ext = it.ext.as_deref();
        let coh = ext.and_then(|e| e.coh.as_ref());
        let rot = ext.and_then(|e| e.geom.as_ref()).and_then(|g| g.rot());
        let gc = ext.and_then(|e| match e.geom.as_ref() {
            Some(ryade::geom::GeomExt::ScGridCo(s)) => Some(s),
            _ => None,
        });
        let o: Option<PyObject> = match field {
            "kr" => coh
                .map(|c| c.kr.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            "ktw" => coh
                .map(|c| c.ktw.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            "unp" => coh
                .map(|c| c.unp.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            "unpMax" => coh
                .map(|c| c.unp_max.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            "normalAdhesion" => coh
                .map(|c| {
                    c.normal_adhesion
                        .into_pyobject(py)
                        .map(|x| x.into_any().unbind())
                })
                .transpose()?,
            "shearAdhesion" => coh
                .map(|c| {
                    c.shear_adhesion
                        .into_pyobject(py)
                        .map(|x| x.into_any().unbind())
                })
                .transpose()?,
            "cohesionBroken" => coh
                .map(|c| {
                    c.cohesion_broken
                        .into_pyobject(py)
                        .map(|x| x.to_owned().into_any().unbind())
                })
                .transpose()?,
            "momentRotationLaw" => coh
                .map(|c| {
                    c.moment_rotation_law
                        .into_pyobject(py)
                        .map(|x| x.to_owned().into_any().unbind())
                })
                .transpose()?,
            "moment_twist" => coh
                .map(|c| {
                    v3(&c.moment_twist)
                        .into_pyobject(py)
                        .map(|x| x.into_any().unbind())
                })
                .transpose()?,
            "moment_bending" => coh
                .map(|c| {
                    v3(&c.moment_bending)
                        .into_pyobject(py)
                        .map(|x| x.into_any().unbind())
                })
                .transpose()?,
            "twist" => rot
                .map(|r| r.twist.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            "bending" => rot
                .map(|r| {
                    v3(&r.bending)
                        .into_pyobject(py)
                        .map(|x| x.into_any().unbind())
                })
                .transpose()?,
            "relPos" => gc
                .map(|g| g.rel_pos.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            "isDuplicate" => gc
                .map(|g| {
                    g.is_duplicate
                        .into_pyobject(py)
                        .map(|x| x.into_any().unbind())
                })
                .transpose()?,
            "trueInt" => gc
                .map(|g| g.true_int.into_pyobject(py).map(|x| x.into_any().unbind()))
                .transpose()?,
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "interactions have no attribute '{}' in ryade",
                    field
                )))
            }
        };
        Ok(o.unwrap_or_else(|| py.None()))
    }
    /// YADE class names of the interaction's geometry and physics.
    fn intr_classes(&self, a: u32, b: u32) -> PyResult<(String, String)> {
        let it = &self.scene.interactions.list[self.intr_index(a, b)?];
        let ext = it.ext.as_deref();
        let g = match ext.and_then(|e| e.geom.as_ref()) {
            Some(ryade::geom::GeomExt::Sc6D(_)) => "ScGeom6D",
            Some(ryade::geom::GeomExt::GridNode { .. }) => "GridNodeGeom6D",
            Some(ryade::geom::GeomExt::ScGridCo(_)) => "ScGridCoGeom",
            Some(ryade::geom::GeomExt::GridCoGridCo(_)) => "GridCoGridCoGeom",
            None => "ScGeom",
        };
        let p = if ext.and_then(|e| e.coh.as_ref()).is_some() {
            "CohFrictPhys"
        } else if ext.and_then(|e| e.viscel.as_ref()).is_some() {
            "ViscElPhys"
        } else if ext.and_then(|e| e.mindlin.as_ref()).is_some() {
            "MindlinPhys"
        } else if ext.and_then(|e| e.luding.as_ref()).is_some() {
            "LudingPhys"
        } else if ext.and_then(|e| e.bubble.as_ref()).is_some() {
            "BubblePhys"
        } else if ext.and_then(|e| e.cpm.as_ref()).is_some() {
            "CpmPhys"
        } else {
            "FrictPhys"
        };
        Ok((g.to_string(), p.to_string()))
    }
    /// A `MindlinPhys` attribute as JSON (None when the physics is not a MindlinPhys or has no such
    /// attribute).
    fn intr_mindlin(&self, a: u32, b: u32, field: &str) -> PyResult<Option<String>> {
        let it = &self.scene.interactions.list[self.intr_index(a, b)?];
        let Some(m) = it.ext.as_deref().and_then(|e| e.mindlin.as_ref()) else {
            return Ok(None);
        };
        use serde_json::json as j;
        let v = match field {
            "kno" => j!(m.kno),
            "kso" => j!(m.kso),
            "maxBendPl" => j!(m.max_bend_pl),
            "normalViscous" => v3json(&m.normal_viscous),
            "shearViscous" => v3json(&m.shear_viscous),
            "shearElastic" => v3json(&m.shear_elastic),
            "usElastic" => v3json(&m.us_elastic),
            "usTotal" => v3json(&m.us_total),
            "momentBend" => v3json(&m.moment_bend),
            "momentTwist" => v3json(&m.moment_twist),
            "radius" => {
                if m.radius.is_nan() {
                    j!("nan")
                } else {
                    j!(m.radius)
                }
            }
            "adhesionForce" => j!(m.adhesion_force),
            "isAdhesive" => j!(m.is_adhesive),
            "isSliding" => j!(m.is_sliding),
            "betan" => j!(m.betan),
            "betas" => j!(m.betas),
            "kr" => j!(m.kr),
            "ktw" => j!(m.ktw),
            _ => return Ok(None),
        };
        Ok(Some(v.to_string()))
    }
    /// A `CpmPhys` attribute as JSON (None when the physics is not a CpmPhys or has no such attribute;
    /// NaN as the string "nan").
    fn intr_cpm(&self, a: u32, b: u32, field: &str) -> PyResult<Option<String>> {
        let it = &self.scene.interactions.list[self.intr_index(a, b)?];
        let Some(c) = it.cpm() else {
            return Ok(None);
        };
        use serde_json::json as j;
        let num = |x: f64| if x.is_nan() { j!("nan") } else { j!(x) };
        let v = match field {
            "omega" => num(c.omega),
            "Fn" => num(c.fn_),
            "Fs" => v3json(&c.fs),
            "epsN" => num(c.eps_n),
            "epsT" => v3json(&c.eps_t),
            "sigmaN" => num(c.sigma_n),
            "sigmaT" => v3json(&c.sigma_t),
            "kappaD" => num(c.kappa_d),
            "epsNPl" => num(c.eps_n_pl),
            "epsTPl" => v3json(&c.eps_t_pl),
            "relResidualStrength" => num(c.rel_residual_strength),
            "E" => num(c.e),
            "G" => num(c.g),
            "tanFrictionAngle" => num(c.tan_friction_angle),
            "undamagedCohesion" => num(c.undamaged_cohesion),
            "crossSection" => num(c.cross_section),
            "refLength" => num(c.ref_length),
            "refPD" => num(c.ref_pd),
            "epsCrackOnset" => num(c.eps_crack_onset),
            "relDuctility" => num(c.rel_ductility),
            "epsFracture" => num(c.eps_fracture),
            "equivStrainShearContrib" => num(c.equiv_strain_shear_contrib),
            "dmgTau" => num(c.dmg_tau),
            "dmgRateExp" => num(c.dmg_rate_exp),
            "dmgStrain" | "dmgOverstress" => j!(0.0),
            "plTau" => num(c.pl_tau),
            "plRateExp" => num(c.pl_rate_exp),
            "isoPrestress" => num(c.iso_prestress),
            "neverDamage" => j!(c.never_damage),
            "damLaw" => j!(c.dam_law),
            "isCohesive" => j!(c.is_cohesive),
            _ => return Ok(None),
        };
        Ok(Some(v.to_string()))
    }
    fn cpm_elastic_energy(&self) -> f64 {
        ryade::utils::cpm_elastic_energy(&self.scene)
    }
    /// Overwrite a stiffness or plasticity attribute of an existing interaction (calibration overrides).
    fn intr_set_scalar(&mut self, a: u32, b: u32, field: &str, v: f64) -> PyResult<()> {
        let k = self.intr_index(a, b)?;
        let it = &mut self.scene.interactions.list[k];
        let nope = || {
            PyKeyError::new_err(format!(
                "setting interaction attribute '{}' is not supported by ryade yet",
                field
            ))
        };
        match field {
            "kn" | "ks" => {
                let p = it
                    .phys
                    .as_mut()
                    .ok_or_else(|| PyKeyError::new_err("the interaction is not real"))?;
                if field == "kn" {
                    p.kn = v
                } else {
                    p.ks = v
                }
            }
            _ => {
                let c = it
                    .ext
                    .as_deref_mut()
                    .and_then(|e| e.coh.as_mut())
                    .ok_or_else(nope)?;
                match field {
                    "kr" => c.kr = v,
                    "ktw" => c.ktw = v,
                    "unp" => c.unp = v,
                    "unpMax" => c.unp_max = v,
                    "momentRotationLaw" => c.moment_rotation_law = v != 0.0,
                    _ => return Err(nope()),
                }
            }
        }
        Ok(())
    }
    /// `utils.createInteraction(id1, id2)`; returns (id1, id2) as stored (after a functor swap).
    fn create_interaction(&mut self, a: usize, b: usize) -> PyResult<(u32, u32)> {
        let k = self
            .scene
            .create_interaction(a, b)
            .map_err(PyRuntimeError::new_err)?;
        let it = &self.scene.interactions.list[k];
        Ok((it.id1, it.id2))
    }
    /// `gridpfacet.gridConnection`: creates the connection body and the node-node bond; returns the body id.
    #[pyo3(signature = (id1, id2, radius, material, mask, cell_dist=None))]
    fn grid_connection(
        &mut self,
        id1: usize,
        id2: usize,
        radius: f64,
        material: usize,
        mask: i32,
        cell_dist: Option<[i32; 3]>,
    ) -> PyResult<usize> {
        ryade::utils::grid_connection(&mut self.scene, id1, id2, radius, material, mask, cell_dist)
            .map_err(PyRuntimeError::new_err)
    }
    fn intr_set_vec3(&mut self, a: u32, b: u32, field: &str, v: V3) -> PyResult<()> {
        let k = self.intr_index(a, b)?;
        let it = &mut self.scene.interactions.list[k];
        let p = it
            .phys
            .as_mut()
            .ok_or_else(|| PyKeyError::new_err("the interaction is not real"))?;
        match field {
            "normalForce" => p.normal_force = vec(v),
            "shearForce" => p.shear_force = vec(v),
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "setting interaction attribute '{}' is not supported by ryade yet",
                    field
                )))
            }
        }
        Ok(())
    }

    // ---- utils ----
    fn pwave_time_step(&self) -> Option<f64> {
        ryade::utils::pwave_time_step(&self.scene)
    }
    fn unbalanced_force(&self, use_max: bool) -> f64 {
        ryade::utils::unbalanced_force(&self.scene, use_max)
    }
    #[pyo3(signature = (volume=None))]
    fn porosity(&self, volume: Option<f64>) -> PyResult<f64> {
        ryade::utils::porosity(&self.scene, volume).map_err(err)
    }
    fn cohesion_moment_elastic_energy(&self, shear: bool) -> f64 {
        ryade::utils::cohesion_moment_elastic_energy(&self.scene, shear)
    }
    fn kinetic_energy(&self) -> f64 {
        ryade::utils::kinetic_energy(&self.scene)
    }
    /// `utils.getStress(volume=0)` (Shop::getStress), rows of the 3x3 tensor.
    #[pyo3(signature = (volume=0.0))]
    fn get_stress(&self, volume: f64) -> PyResult<[[f64; 3]; 3]> {
        let m = ryade::peri_triax::get_stress(&self.scene, volume).map_err(err)?;
        Ok(rows3(&m))
    }
    fn aabb_extrema(&self) -> Option<(V3, V3)> {
        ryade::utils::aabb_extrema(&self.scene).map(|(a, b)| (v3(&a), v3(&b)))
    }
    fn check_time_step(&self) -> PyResult<()> {
        ryade::utils::check_time_step(&self.scene).map_err(PyValueError::new_err)
    }

    // ---- whole scene ----
    fn save_tmp(&mut self, name: &str) {
        self.saved.insert(name.to_string(), self.scene.clone());
    }
    fn load_tmp(&mut self, name: &str) -> PyResult<()> {
        let s = self.saved.get(name).ok_or_else(|| {
            PyKeyError::new_err(format!("no scene saved with O.saveTmp('{}')", name))
        })?;
        self.scene = s.clone();
        self.cursor = None;
        Ok(())
    }
    fn scene_json(&self, steps: u64) -> String {
        scene_json::to_value(&self.scene, steps).to_string()
    }
}

fn spheres_of(spheres: Vec<(V3, f64)>) -> Vec<(Vec3, f64)> {
    spheres.into_iter().map(|(c, r)| (vec(c), r)).collect()
}

/// Exact sphere-box intersection porosity (periodic images in x, y when given).
#[pyfunction]
#[pyo3(signature = (spheres, lo, hi, periodic_xy=None))]
fn box_porosity(spheres: Vec<(V3, f64)>, lo: V3, hi: V3, periodic_xy: Option<(f64, f64)>) -> f64 {
    ryade::porosity::box_porosity(&spheres_of(spheres), &vec(lo), &vec(hi), periodic_xy)
}

/// `utils.voxelPorosity` (dynamic spheres only, as YADE).
#[pyfunction]
fn voxel_porosity(spheres: Vec<(V3, f64)>, resolution: i32, start: V3, end: V3) -> PyResult<f64> {
    ryade::porosity::voxel_porosity(&spheres_of(spheres), resolution, &vec(start), &vec(end))
        .map_err(err)
}

/// Result of `make_cloud`: (count, spheres, cell_size, is_periodic, applied_psd_scaling, warnings).
type CloudOut = (usize, Vec<(V3, f64)>, Option<V3>, bool, f64, Vec<String>);

/// `SpherePack.makeCloud` on a pack holding `spheres` (bit-exact with YADE for seed >= 0).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (spheres, cell_size, min_corner, max_corner, r_mean, r_rel_fuzz, num, periodic, porosity, psd_sizes, psd_cumm, distribute_mass, seed, h_size))]
fn make_cloud(
    spheres: Vec<(V3, f64)>,
    cell_size: Option<V3>,
    min_corner: V3,
    max_corner: V3,
    r_mean: f64,
    r_rel_fuzz: f64,
    num: i32,
    periodic: bool,
    porosity: f64,
    psd_sizes: Vec<f64>,
    psd_cumm: Vec<f64>,
    distribute_mass: bool,
    seed: i32,
    h_size: Option<[[f64; 3]; 3]>,
) -> PyResult<CloudOut> {
    let mut sp = ryade::pack::SpherePack::new();
    for (c, r) in spheres {
        sp.add(vec(c), r);
    }
    sp.cell_size = cell_size.map(vec);
    sp.is_periodic = cell_size.is_some();
    let p = ryade::pack::CloudParams {
        min_corner: vec(min_corner),
        max_corner: vec(max_corner),
        r_mean,
        r_rel_fuzz,
        num,
        periodic,
        porosity,
        psd_sizes,
        psd_cumm,
        distribute_mass,
        seed,
        h_size: h_size.map(|h| ryade::math::Mat3::from_fn(|i, j| h[i][j])),
    };
    let n = sp
        .make_cloud(&p)
        .map_err(|e| PyValueError::new_err(format!("makeCloud: {:#}", e)))?;
    Ok((
        n,
        sp.spheres.iter().map(|(c, r)| (v3(c), *r)).collect(),
        sp.cell_size.map(|c| v3(&c)),
        sp.is_periodic,
        sp.applied_psd_scaling,
        sp.warnings.clone(),
    ))
}

/// `Shop::inscribedCircleCenter`, in YADE's evaluation order.
#[pyfunction]
fn inscribed_circle_center(v0: V3, v1: V3, v2: V3) -> V3 {
    v3(&ryade::utils::inscribed_circle_center(
        &vec(v0),
        &vec(v1),
        &vec(v2),
    ))
}

/// Change one attribute of a built-in engine (value as JSON) without resetting its state; a member of a
/// `CombinedKinematicEngine` is addressed as `comb.N.attr`.
fn engine_set_attr(e: &mut Engine, key: &str, v: &Value) -> PyResult<()> {
    let num = || {
        v.as_f64()
            .ok_or_else(|| PyValueError::new_err(format!("{} must be a number", key)))
    };
    let boolean = || {
        v.as_bool()
            .ok_or_else(|| PyValueError::new_err(format!("{} must be a bool", key)))
    };
    let unsupported = |cls: &str| {
        PyKeyError::new_err(format!(
            "changing {}.{} during a run is not supported by ryade yet",
            cls, key
        ))
    };
    match e {
        Engine::Newton(n) => match key {
            "damping" => n.damping = num()?,
            "gravity" => {
                let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                n.gravity = vec(a)
            }
            "dampGravity" => n.damp_gravity = boolean()?,
            _ => return Err(unsupported("NewtonIntegrator")),
        },
        Engine::TimeStepper(t) => match key {
            "active" => t.active = boolean()?,
            "timeStepUpdateInterval" => t.time_step_update_interval = num()? as u32,
            "defaultDt" => t.default_dt = num()?,
            "maxDt" => t.max_dt = num()?,
            "timestepSafetyCoefficient" => t.timestep_safety_coefficient = num()?,
            "previousDt" => t.previous_dt = num()?,
            _ => return Err(unsupported("GlobalStiffnessTimeStepper")),
        },
        Engine::Translation(t) => match key {
            "ids" => t.ids = serde_json::from_value(v.clone()).map_err(err)?,
            "velocity" => t.velocity = num()?,
            "translationAxis" => {
                let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                t.translation_axis = vec(a) // normalised on the Python side
            }
            _ => return Err(unsupported("TranslationEngine")),
        },
        Engine::Rotation(r) => match key {
            "ids" => r.ids = serde_json::from_value(v.clone()).map_err(err)?,
            "angularVelocity" => r.angular_velocity = num()?,
            "rotateAroundZero" => r.rotate_around_zero = boolean()?,
            "rotationAxis" | "zeroPoint" => {
                let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                if key == "rotationAxis" {
                    r.rotation_axis = vec(a) // normalised on the Python side
                } else {
                    r.zero_point = vec(a)
                }
            }
            _ => return Err(unsupported("RotationEngine")),
        },
        Engine::ServoPid(s) => match key {
            "ids" => s.ids = serde_json::from_value(v.clone()).map_err(err)?,
            "axis" | "current" | "translationAxis" => {
                let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                match key {
                    "axis" => s.axis = vec(a),
                    "current" => s.current = vec(a),
                    _ => s.translation_axis = vec(a),
                }
            }
            "target" => s.target = num()?,
            "kP" => s.kp = num()?,
            "kI" => s.ki = num()?,
            "kD" => s.kd = num()?,
            "iTerm" => s.i_term = num()?,
            "curVel" => s.cur_vel = num()?,
            "errorCur" => s.error_cur = num()?,
            "errorPrev" => s.error_prev = num()?,
            "maxVelocity" => s.max_velocity = num()?,
            "iterPeriod" => s.iter_period = num()? as i64,
            "iterPrevStart" => s.iter_prev_start = num()? as i64,
            "velocity" => s.velocity = num()?,
            _ => return Err(unsupported("ServoPIDController")),
        },
        // every attribute of the ryade extension is live (src/piston.rs `PistonController::set`)
        Engine::Piston(pc) => pc.set(key, v).map_err(PyValueError::new_err)?,
        Engine::PeriTriax(p) => peri_triax_set(p, key, v).map_err(|e| match e {
            None => unsupported("PeriTriaxController"),
            Some(e) => PyValueError::new_err(e),
        })?,
        Engine::Collider(c) => match key {
            "verletDist" => c.p.verlet_dist = num()?,
            "allowBiggerThanPeriod" => c.p.allow_bigger_than_period = boolean()?,
            "doSort" => c.do_sort = boolean()?,
            "targetInterv" => c.p.target_interv = num()? as i32,
            // the next bound update uses it, as YADE's functor does
            "Bo1_Sphere_Aabb.aabbEnlargeFactor" if c.p.bounds.sphere.is_some() => {
                c.p.bounds.sphere = Some(num()?)
            }
            _ => return Err(unsupported("InsertionSortCollider")),
        },
        Engine::Helix(h) => match key {
            "linearVelocity" => h.linear_velocity = num()?,
            "angleTurned" => h.angle_turned = num()?,
            _ => {
                let mut r = Engine::Rotation(Box::new(h.rot.clone()));
                engine_set_attr(&mut r, key, v).map_err(|_| unsupported("HelixEngine"))?;
                if let Engine::Rotation(r) = r {
                    h.rot = *r;
                }
            }
        },
        Engine::Force(f) => match key {
            "ids" => f.ids = serde_json::from_value(v.clone()).map_err(err)?,
            "force" => {
                let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                f.force = vec(a)
            }
            _ => return Err(unsupported("ForceEngine")),
        },
        Engine::HarmonicForce(h) => match key {
            "ids" => h.ids = serde_json::from_value(v.clone()).map_err(err)?,
            "A" | "f" | "fi" => {
                let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                match key {
                    "A" => h.a = vec(a),
                    "f" => h.f = vec(a),
                    _ => h.fi = vec(a),
                }
            }
            _ => return Err(unsupported("HarmonicForceEngine")),
        },
        Engine::InteractionLoop(il) => {
            // a number (a constant MatchMaker) or a MatchMaker object (its JSON)
            let opt = || -> PyResult<Option<ryade::phys::MatchMaker>> {
                if v.is_null() {
                    Ok(None)
                } else if v.is_number() {
                    Ok(Some(ryade::phys::MatchMaker {
                        matches: Vec::new(),
                        algo: "val".into(),
                        val: num()?,
                    }))
                } else {
                    scene_json::match_maker_of(v)
                        .map(Some)
                        .map_err(|e| PyValueError::new_err(e.to_string()))
                }
            };
            match key.split_once('.') {
                // the geometry functors' detection factor (read at every call, as in YADE)
                Some(("Ig2_Sphere_Sphere_ScGeom", "interactionDetectionFactor"))
                    if il.sphere_sphere.is_some() =>
                {
                    il.sphere_sphere
                        .as_mut()
                        .unwrap()
                        .interaction_detection_factor = num()?
                }
                Some(("Ig2_Sphere_Sphere_ScGeom6D", "interactionDetectionFactor"))
                    if il.sphere_sphere_6d.is_some() =>
                {
                    il.sphere_sphere_6d
                        .as_mut()
                        .unwrap()
                        .ss
                        .interaction_detection_factor = num()?
                }
                Some((
                    "Ig2_Box_Sphere_ScGeom" | "Ig2_Box_Sphere_ScGeom6D",
                    "interactionDetectionFactor",
                )) if il.box_sphere.is_some() => {
                    il.box_sphere.as_mut().unwrap().interaction_detection_factor = num()?
                }
                // fresh callback objects: their accumulators start at zero, as YADE's new instances
                None if key == "callbacks" => {
                    let arr = v
                        .as_array()
                        .ok_or_else(|| PyValueError::new_err("callbacks must be a list"))?;
                    let mut cbs = Vec::new();
                    for cb in arr {
                        match cb.get("class").and_then(Value::as_str) {
                            Some("SumIntrForcesCb") => cbs.push(Default::default()),
                            other => {
                                return Err(PyKeyError::new_err(format!(
                                    "InteractionLoop callback {:?} is not supported by ryade yet",
                                    other
                                )))
                            }
                        }
                    }
                    il.sum_intr_forces_cb = cbs;
                }
                Some(("Ip2_FrictMat_FrictMat_MindlinPhys", k)) if il.mindlin_phys.is_some() => {
                    let p = il.mindlin_phys.as_mut().unwrap();
                    match k {
                        "gamma" => p.gamma = num()?,
                        "eta" => p.eta = num()?,
                        "krot" => p.krot = num()?,
                        "ktwist" => p.ktwist = num()?,
                        "en" => p.en = opt()?,
                        "es" => p.es = opt()?,
                        "betan" => p.betan = opt()?,
                        "betas" => p.betas = opt()?,
                        "frictAngle" => p.frict_angle = opt()?,
                        _ => return Err(unsupported("InteractionLoop")),
                    }
                }
                Some(("Law2_ScGeom_MindlinPhys_Mindlin", k)) if il.mindlin.is_some() => {
                    let p = il.mindlin.as_mut().unwrap();
                    match k {
                        "includeAdhesion" => p.include_adhesion = boolean()?,
                        "includeMoment" => p.include_moment = boolean()?,
                        "neverErase" => p.never_erase = boolean()?,
                        _ => return Err(unsupported("InteractionLoop")),
                    }
                }
                _ => return Err(unsupported("InteractionLoop")),
            }
        }
        Engine::Kinematic(k) => {
            use ryade::kinematic::KinematicPart as K;
            let list = || -> PyResult<Vec<f64>> { serde_json::from_value(v.clone()).map_err(err) };
            match (&mut **k, key) {
                (K::InterpolatingHelix(h), "times") => h.times = list()?,
                (K::InterpolatingHelix(h), "angularVelocities") => h.angular_velocities = list()?,
                (K::InterpolatingHelix(h), "wrap") => h.wrap = boolean()?,
                (K::InterpolatingHelix(h), "slope") => h.slope = num()?,
                (K::InterpolatingHelix(h), _) => {
                    let mut e = Engine::Helix(Box::new(h.helix.clone()));
                    engine_set_attr(&mut e, key, v)
                        .map_err(|_| unsupported("InterpolatingHelixEngine"))?;
                    if let Engine::Helix(x) = e {
                        h.helix = *x;
                    }
                }
                (K::BicyclePedal(b), "ids") => {
                    b.ids = serde_json::from_value(v.clone()).map_err(err)?
                }
                (K::BicyclePedal(b), "angularVelocity") => b.angular_velocity = num()?,
                (K::BicyclePedal(b), "radius") => b.radius = num()?,
                (K::BicyclePedal(b), "fi") => b.fi = num()?,
                (K::BicyclePedal(b), "rotationAxis") => {
                    let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                    b.rotation_axis = vec(a) // normalised on the Python side
                }
                (k, _) => return Err(unsupported(k.class_name())),
            }
        }
        Engine::DirectedForce(f) => {
            let list = || -> PyResult<Vec<f64>> { serde_json::from_value(v.clone()).map_err(err) };
            match key {
                "ids" => f.base.ids = serde_json::from_value(v.clone()).map_err(err)?,
                "times" => f.times = list()?,
                "magnitudes" => f.magnitudes = list()?,
                "wrap" => f.wrap = boolean()?,
                "force" | "direction" => {
                    let a: V3 = serde_json::from_value(v.clone()).map_err(err)?;
                    if key == "force" {
                        f.base.force = vec(a)
                    } else {
                        f.direction = vec(a)
                    }
                }
                _ => return Err(unsupported("InterpolatingDirectedForceEngine")),
            }
        }
        Engine::Hydro(h) => h.set(key, v).map_err(|e| match e {
            None => unsupported("HydroForceEngine"),
            Some(e) => PyValueError::new_err(e),
        })?,
        Engine::TriaxialStress(t) => t.set(key, v).map_err(|e| match e {
            None => unsupported("TriaxialStressController"),
            Some(e) => PyValueError::new_err(e),
        })?,
        Engine::CombinedKinematic(c) => {
            if key == "ids" {
                c.ids = serde_json::from_value(v.clone()).map_err(err)?;
            } else if let Some((n, sub)) = key
                .strip_prefix("comb.")
                .and_then(|r| r.split_once('.'))
                .and_then(|(n, sub)| n.parse::<usize>().ok().map(|n| (n, sub)))
                .filter(|(n, _)| *n < c.comb.len())
            {
                if sub == "dead" {
                    c.comb_dead[n] = boolean()?;
                } else {
                    let mut part = part_engine(c.comb[n].clone());
                    engine_set_attr(&mut part, sub, v)?;
                    c.comb[n] = engine_part(part);
                }
            } else {
                return Err(unsupported("CombinedKinematicEngine"));
            }
        }
        other => return Err(unsupported(other.class_name())),
    }
    Ok(())
}

/// Read an attribute of a built-in engine (JSON); a member of a `CombinedKinematicEngine` as
/// `comb.N.attr`.
fn engine_get_attr(e: &Engine, key: &str) -> PyResult<Value> {
    let v = match (e, key) {
        (Engine::Newton(n), "damping") => serde_json::json!(n.damping),
        (Engine::Newton(n), "gravity") => {
            serde_json::json!([n.gravity[0], n.gravity[1], n.gravity[2]])
        }
        (Engine::Newton(n), "maxVelocitySq") => serde_json::json!(n.max_velocity_sq),
        (Engine::Newton(n), "prevVelGrad") => {
            let m = &n.prev_vel_grad;
            serde_json::json!([
                [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
                [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
                [m[(2, 0)], m[(2, 1)], m[(2, 2)]]
            ])
        }
        (Engine::Collider(c), "verletDist") => serde_json::json!(c.p.verlet_dist),
        (Engine::Collider(c), "numAction") => serde_json::json!(c.num_action),
        (Engine::TimeStepper(t), "previousDt") => serde_json::json!(t.previous_dt),
        (Engine::TimeStepper(t), "defaultDt") => serde_json::json!(t.default_dt),
        (Engine::TimeStepper(t), "active") => serde_json::json!(t.active),
        (Engine::Translation(t), "ids") => serde_json::json!(t.ids),
        (Engine::Translation(t), "velocity") => serde_json::json!(t.velocity),
        (Engine::Translation(t), "translationAxis") => v3json(&t.translation_axis),
        (Engine::Rotation(r), "ids") => serde_json::json!(r.ids),
        (Engine::Rotation(r), "angularVelocity") => serde_json::json!(r.angular_velocity),
        (Engine::Rotation(r), "rotationAxis") => v3json(&r.rotation_axis),
        (Engine::Rotation(r), "rotateAroundZero") => serde_json::json!(r.rotate_around_zero),
        (Engine::Rotation(r), "zeroPoint") => v3json(&r.zero_point),
        (Engine::Piston(pc), k) => pc.get(k).map_err(PyKeyError::new_err)?,
        (Engine::PeriTriax(p), k) => peri_triax_get(p, k).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "PeriTriaxController has no readable attribute '{}' in ryade",
                k
            ))
        })?,
        (Engine::ServoPid(s), k) => match k {
            "ids" => serde_json::json!(s.ids),
            "axis" => v3json(&s.axis),
            "current" => v3json(&s.current),
            "translationAxis" => v3json(&s.translation_axis),
            "target" => serde_json::json!(s.target),
            "kP" => serde_json::json!(s.kp),
            "kI" => serde_json::json!(s.ki),
            "kD" => serde_json::json!(s.kd),
            "iTerm" => serde_json::json!(s.i_term),
            "curVel" => serde_json::json!(s.cur_vel),
            "errorCur" => serde_json::json!(s.error_cur),
            "errorPrev" => serde_json::json!(s.error_prev),
            "maxVelocity" => serde_json::json!(s.max_velocity),
            "iterPeriod" => serde_json::json!(s.iter_period),
            "iterPrevStart" => serde_json::json!(s.iter_prev_start),
            "velocity" => serde_json::json!(s.velocity),
            _ => {
                return Err(PyKeyError::new_err(format!(
                    "ServoPIDController has no readable attribute '{}' in ryade",
                    key
                )))
            }
        },
        (Engine::Helix(h), "linearVelocity") => serde_json::json!(h.linear_velocity),
        (Engine::Helix(h), "angleTurned") => serde_json::json!(h.angle_turned),
        (Engine::Helix(h), k) => engine_get_attr(&Engine::Rotation(Box::new(h.rot.clone())), k)?,
        (Engine::Force(f), "ids") => serde_json::json!(f.ids),
        (Engine::Force(f), "force") => v3json(&f.force),
        (Engine::HarmonicForce(h), "ids") => serde_json::json!(h.ids),
        (Engine::HarmonicForce(h), "A") => v3json(&h.a),
        (Engine::HarmonicForce(h), "f") => v3json(&h.f),
        (Engine::HarmonicForce(h), "fi") => v3json(&h.fi),
        (Engine::Kinematic(k), key) => {
            use ryade::kinematic::KinematicPart as K;
            match (&**k, key) {
                (K::InterpolatingHelix(h), "times") => serde_json::json!(h.times),
                (K::InterpolatingHelix(h), "angularVelocities") => {
                    serde_json::json!(h.angular_velocities)
                }
                (K::InterpolatingHelix(h), "wrap") => serde_json::json!(h.wrap),
                (K::InterpolatingHelix(h), "slope") => serde_json::json!(h.slope),
                (K::InterpolatingHelix(h), _) => {
                    engine_get_attr(&Engine::Helix(Box::new(h.helix.clone())), key)?
                }
                (K::BicyclePedal(b), "ids") => serde_json::json!(b.ids),
                (K::BicyclePedal(b), "angularVelocity") => serde_json::json!(b.angular_velocity),
                (K::BicyclePedal(b), "radius") => serde_json::json!(b.radius),
                (K::BicyclePedal(b), "fi") => serde_json::json!(b.fi),
                (K::BicyclePedal(b), "rotationAxis") => v3json(&b.rotation_axis),
                (k, _) => {
                    return Err(PyKeyError::new_err(format!(
                        "{} has no readable attribute '{}' in ryade",
                        k.class_name(),
                        key
                    )))
                }
            }
        }
        (Engine::DirectedForce(f), "ids") => serde_json::json!(f.base.ids),
        (Engine::DirectedForce(f), "force") => v3json(&f.base.force),
        (Engine::DirectedForce(f), "direction") => v3json(&f.direction),
        (Engine::DirectedForce(f), "times") => serde_json::json!(f.times),
        (Engine::DirectedForce(f), "magnitudes") => serde_json::json!(f.magnitudes),
        (Engine::DirectedForce(f), "wrap") => serde_json::json!(f.wrap),
        (Engine::TriaxialStress(t), k) => t.get(k).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "TriaxialStressController has no readable attribute '{}' in ryade",
                k
            ))
        })?,
        (Engine::CombinedKinematic(c), "ids") => serde_json::json!(c.ids),
        (Engine::CombinedKinematic(c), k)
            if k.strip_prefix("comb.")
                .and_then(|r| r.split_once('.'))
                .and_then(|(n, _)| n.parse::<usize>().ok())
                .is_some_and(|n| n < c.comb.len()) =>
        {
            let (n, sub) = k["comb.".len()..].split_once('.').unwrap();
            let n: usize = n.parse().unwrap();
            if sub == "dead" {
                serde_json::json!(c.comb_dead[n])
            } else {
                engine_get_attr(&part_engine(c.comb[n].clone()), sub)?
            }
        }
        _ => {
            return Err(PyKeyError::new_err(format!(
                "{} has no readable attribute '{}' in ryade",
                e.class_name(),
                key
            )))
        }
    };
    Ok(v)
}

/// A member of a `CombinedKinematicEngine` as the engine it stands for (to reuse the attribute code).
fn part_engine(p: ryade::kinematic::KinematicPart) -> Engine {
    use ryade::kinematic::KinematicPart as K;
    match p {
        K::Translation(t) => Engine::Translation(Box::new(t)),
        K::Rotation(r) => Engine::Rotation(Box::new(r)),
        K::Helix(h) => Engine::Helix(Box::new(h)),
        K::ServoPid(s) => Engine::ServoPid(Box::new(s)),
        k => Engine::Kinematic(Box::new(k)),
    }
}

/// The inverse of `part_engine` (only kinematic engines come back).
fn engine_part(e: Engine) -> ryade::kinematic::KinematicPart {
    use ryade::kinematic::KinematicPart as K;
    match e {
        Engine::Translation(t) => K::Translation(*t),
        Engine::Rotation(r) => K::Rotation(*r),
        Engine::Helix(h) => K::Helix(*h),
        Engine::ServoPid(s) => K::ServoPid(*s),
        Engine::Kinematic(k) => *k,
        _ => unreachable!("engine_part on a non-kinematic engine"),
    }
}

#[pymodule]
fn _ryade(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Sim>()?;
    m.add_class::<StateBase>()?;
    m.add_class::<OmegaBase>()?;
    m.add_class::<FieldAccess>()?;
    m.add_function(wrap_pyfunction!(_install_vector_getitem, m)?)?;
    m.add_function(wrap_pyfunction!(_state_setattr, m)?)?;
    m.add_function(wrap_pyfunction!(_forces_accessor, m)?)?;
    m.add_function(wrap_pyfunction!(box_porosity, m)?)?;
    m.add_function(wrap_pyfunction!(voxel_porosity, m)?)?;
    m.add_function(wrap_pyfunction!(make_cloud, m)?)?;
    m.add_function(wrap_pyfunction!(inscribed_circle_center, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

fn v3json(v: &ryade::math::Vec3) -> Value {
    serde_json::json!([v[0], v[1], v[2]])
}

/// NaN as JSON null (YADE's unset `mass` and `currUnbalanced`).
fn num_json(x: f64) -> Value {
    if x.is_nan() {
        Value::Null
    } else {
        serde_json::json!(x)
    }
}

/// Read a PeriTriaxController attribute (JSON), None for an unknown name.
fn peri_triax_get(p: &ryade::peri_triax::PeriTriax, k: &str) -> Option<Value> {
    let m = &p.stress_tensor;
    Some(match k {
        "dynCell" => serde_json::json!(p.dyn_cell),
        "goal" => v3json(&p.goal),
        "stressMask" => serde_json::json!(p.stress_mask),
        "maxStrainRate" => v3json(&p.max_strain_rate),
        "maxUnbalanced" => serde_json::json!(p.max_unbalanced),
        "absStressTol" => serde_json::json!(p.abs_stress_tol),
        "relStressTol" => serde_json::json!(p.rel_stress_tol),
        "growDamping" => serde_json::json!(p.grow_damping),
        "globUpdate" => serde_json::json!(p.glob_update),
        "doneHook" => serde_json::json!(p.done_hook),
        "maxBodySpan" => v3json(&p.max_body_span),
        "stressTensor" => serde_json::json!(rows3(m)),
        "stress" => v3json(&p.stress),
        "strain" => v3json(&p.strain),
        "strainRate" => v3json(&p.strain_rate),
        "stiff" => v3json(&p.stiff),
        "currUnbalanced" => num_json(p.curr_unbalanced),
        "prevGrow" => v3json(&p.prev_grow),
        "mass" => num_json(p.mass),
        "externalWork" => serde_json::json!(p.external_work),
        _ => return None,
    })
}

/// Set a PeriTriaxController attribute from JSON (null = NaN). Err(None): unknown attribute.
fn peri_triax_set(
    p: &mut ryade::peri_triax::PeriTriax,
    k: &str,
    v: &Value,
) -> Result<(), Option<String>> {
    let num = || -> Result<f64, Option<String>> {
        if v.is_null() {
            return Ok(f64::NAN);
        }
        v.as_f64()
            .ok_or_else(|| Some(format!("PeriTriaxController.{} must be a number", k)))
    };
    let v3 = || -> Result<Vec3, Option<String>> {
        let a: V3 = serde_json::from_value(v.clone())
            .map_err(|_| Some(format!("PeriTriaxController.{} must be 3 numbers", k)))?;
        Ok(vec(a))
    };
    match k {
        "dynCell" => {
            p.dyn_cell = v
                .as_bool()
                .ok_or_else(|| Some("PeriTriaxController.dynCell must be a bool".to_string()))?
        }
        "goal" => p.goal = v3()?,
        "stressMask" => p.stress_mask = num()? as i32,
        "maxStrainRate" => p.max_strain_rate = v3()?,
        "maxUnbalanced" => p.max_unbalanced = num()?,
        "absStressTol" => p.abs_stress_tol = num()?,
        "relStressTol" => p.rel_stress_tol = num()?,
        "growDamping" => p.grow_damping = num()?,
        "globUpdate" => p.glob_update = num()? as i32,
        "doneHook" => {
            p.done_hook = v
                .as_str()
                .ok_or_else(|| Some("PeriTriaxController.doneHook must be a string".to_string()))?
                .to_string()
        }
        "maxBodySpan" => p.max_body_span = v3()?,
        "stressTensor" => {
            let r: [[f64; 3]; 3] = serde_json::from_value(v.clone()).map_err(|_| {
                Some("PeriTriaxController.stressTensor must be a 3x3 matrix".to_string())
            })?;
            p.stress_tensor = ryade::math::Mat3::from_fn(|i, j| r[i][j]);
        }
        "stress" => p.stress = v3()?,
        "strain" => p.strain = v3()?,
        "strainRate" => p.strain_rate = v3()?,
        "stiff" => p.stiff = v3()?,
        "currUnbalanced" => p.curr_unbalanced = num()?,
        "prevGrow" => p.prev_grow = v3()?,
        "mass" => p.mass = num()?,
        "externalWork" => p.external_work = num()?,
        _ => return Err(None),
    }
    Ok(())
}

/// A 3x3 matrix as its rows (what Python's Matrix3 is built from).
fn rows3(m: &ryade::math::Mat3) -> [[f64; 3]; 3] {
    [
        [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
        [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
        [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
    ]
}
