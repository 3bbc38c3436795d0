/*
 * progsim — progressive (level-of-detail) simulation of cloth, thin shells and solids.
 *
 * The C ABI: opaque handles, status codes, caller-provided buffers. C99, no inline code.
 *
 * Conventions (every call follows them):
 * - Units are SI: metres, seconds, kilograms, pascals, radians.
 * - Positions are row-major (n × 3) doubles (x0 y0 z0 x1 y1 z1 ...); faces are row-major
 *   (m × 3) int32_t vertex indices, counter-clockwise seen from the front.
 * - Every fallible call returns a ps_status. PS_OK is 0. On failure, nothing the caller
 *   owns was modified (output buffers and out-pointers keep their previous contents), and a
 *   message naming the problem is available from ps_sim_last_error() or
 *   ps_hierarchy_last_error() for calls on a handle, and from ps_last_error() for calls that
 *   had no usable handle (failed creates, NULL handles). No call aborts, exits, prints, or
 *   lets a C++ exception escape.
 * - Arrays out: call with out == NULL (capacity ignored) to learn the size, then again with a
 *   buffer of at least that many elements. A too-small buffer gives
 *   PS_ERROR_BUFFER_TOO_SMALL and the required size.
 * - Ownership: "caller owns" means the caller must destroy it with the named function;
 *   "borrowed" pointers stay valid until the event named and must not be freed.
 *
 * Thread contract: one handle is used by one thread at a time (calls on the same handle
 * must not overlap; every call, even a getter, stores its error message in the handle, and a
 * successful call clears it, so copy a message before the next call). Distinct handles may be used
 * from distinct threads concurrently; a handle may move between threads. A simulation reads its
 * hierarchy, so a hierarchy shared by simulations on several threads must not be destroyed while
 * any of them runs. Callbacks run on the calling thread and must not call back into progsim.
 */
#ifndef PROGSIM_H
#define PROGSIM_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#if defined(PROGSIM_BUILDING)
#define PS_API __declspec(dllexport)
#else
#define PS_API __declspec(dllimport)
#endif
#else
#define PS_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- version -------------- */

#define PS_VERSION_MAJOR 0
#define PS_VERSION_MINOR 20
#define PS_VERSION_PATCH 0
/** The header's version packed as major·10000 + minor·100 + patch. */
#define PS_VERSION_HEADER (PS_VERSION_MAJOR * 10000 + PS_VERSION_MINOR * 100 + PS_VERSION_PATCH)

/** The library's version, packed like PS_VERSION_HEADER. Thread-safe. */
PS_API int32_t ps_version(void);

/** The library's version as text, e.g. "0.1.0". Borrowed, static. Thread-safe. */
PS_API const char* ps_version_string(void);

/**
 * Checks that the library loaded at run time can serve a caller compiled against header
 * version `header_version` (pass PS_VERSION_HEADER). Same major version and a library minor
 * version at least the header's → PS_OK; before 1.0 the minor versions must be equal (a 0.x
 * minor may grow the structs the library fills). Otherwise PS_ERROR_VERSION_MISMATCH with both
 * versions in ps_last_error(). Bindings call it once when they load. Thread-safe.
 */
PS_API int32_t ps_check_version(int32_t header_version);

/* ---------------------------------------------------------------- status --------------- */

/** Result of every fallible call. Values are stable across versions. */
/* Functions return int32_t, not the enum: enums with a _FORCE32 member may be unsigned in a
 * binding's generated types, while status values are compared as int32_t. */
typedef enum ps_status {
  PS_OK = 0,
  PS_ERROR_INVALID_ARGUMENT = 1,   /**< a parameter is NaN, out of range or nonsense */
  PS_ERROR_INVALID_MESH = 2,       /**< a mesh fails validation; names the first bad element */
  PS_ERROR_INVALID_SCENE = 3,      /**< a scene description is malformed (typo, missing field) */
  PS_ERROR_IO = 4,                 /**< a file cannot be read or written */
  PS_ERROR_NUMERICAL = 5,          /**< the solver failed (non-finite values, factorization) */
  PS_ERROR_WRONG_CALL_ORDER = 6,   /**< the call needs another call first */
  PS_ERROR_OUT_OF_RANGE = 7,       /**< a level, handle or index does not exist */
  PS_ERROR_CANCELLED = 8,          /**< the progress callback asked to stop */
  PS_ERROR_INTERSECTING = 9,       /**< a configuration intersects itself or another body */
  PS_ERROR_INTERNAL = 10,          /**< a bug in progsim; please report the message */
  PS_ERROR_NULL_ARGUMENT = 11,     /**< a required pointer or handle is NULL */
  PS_ERROR_BUFFER_TOO_SMALL = 12,  /**< an output buffer's capacity is below the size needed */
  PS_ERROR_UNINITIALIZED_DEF = 13, /**< a def-struct was not filled by its *_def_init() */
  PS_ERROR_VERSION_MISMATCH = 14,  /**< header and library versions are incompatible */
  PS_ERROR_OUT_OF_MEMORY = 15,     /**< an allocation failed */
  PS_ERROR_UNSUPPORTED = 16,       /**< valid request that this version cannot do yet */
  PS_STATUS_FORCE32 = 0x7fffffff
} ps_status;

/** Stable short name of a status ("PS_ERROR_INVALID_MESH", ...). Borrowed, static. */
PS_API const char* ps_status_name(int32_t status);

/**
 * Message of the last failure on the calling thread of a call that had no usable handle
 * (a create, or a call given a NULL handle), or of ps_check_version(). "" if none. Borrowed
 * until the next progsim call on this thread.
 */
PS_API const char* ps_last_error(void);

/* ---------------------------------------------------------------- threads -------------- */

/**
 * Threads of progsim's parallel loops, for the whole process. `threads` from 1 to 1024 fixes
 * the count; 0 (the default) lets the library choose: the processors this process may run on
 * that other processes leave idle, sampled from /proc/stat every 0.25 s while it computes, so
 * that a loaded machine does not slow it down without OMP_WAIT_POLICY=passive (idle OpenMP
 * threads otherwise spin on the core the work needs). OMP_NUM_THREADS, if set, caps the
 * automatic count. Any other value: PS_ERROR_INVALID_ARGUMENT (message in ps_last_error()),
 * the setting unchanged. Takes effect at the next parallel loop. Thread-safe.
 */
PS_API int32_t ps_set_threads(int32_t threads);

/**
 * The setting of ps_set_threads() (0: automatic) into *setting, and the threads a large
 * parallel loop gets now into *current. Either pointer may be NULL. Thread-safe.
 */
PS_API int32_t ps_get_threads(int32_t* setting, int32_t* current);

/**
 * Progress of long calls: called after each unit of work with done/total units and the
 * phase ("decimation" and "expansion coloring" while a hierarchy is built, in percent;
 * "preview" for ps_sim_step_preview(), in steps; "refine" for ps_sim_refine(): in steps of the
 * finer level for a progressive animation, else 0 of 1 then 1 of 1). Return 0
 * to continue, non-zero to cancel: the call then returns PS_ERROR_CANCELLED (also when the
 * last unit was done), keeping the state of the last completed step. The callback must not
 * call the simulation that is running (such calls return PS_ERROR_WRONG_CALL_ORDER); other
 * handles and the handle-free calls are fine.
 */
typedef int32_t (*ps_progress_fn)(void* user_data, int32_t done, int32_t total, const char* phase);

/* ---------------------------------------------------------------- hierarchy ------------ */

/** A mesh hierarchy: level 0 is the coarsest, level num_levels − 1 the user's mesh. */
typedef struct ps_hierarchy ps_hierarchy;

/** How to build a hierarchy. Fill with ps_hierarchy_def_init(), then change fields. */
typedef struct ps_hierarchy_def {
  /** Target vertex count of each level below the finest (distinct, each at least 4 and
   *  below the mesh's; any order, level 0 gets the smallest).
   *  Nullable: NULL with num_coarse_levels = 0 (the default) gives one level, the input
   *  mesh itself. Borrowed during the create call only. */
  const int32_t* coarse_vertex_counts;
  /** Number of entries in coarse_vertex_counts. Default 0. */
  int32_t num_coarse_levels;
  /** Nullable (default): called while the hierarchy is built (see ps_progress_fn). */
  ps_progress_fn progress;
  /** Passed back to progress unchanged. Default NULL. */
  void* progress_user_data;
  /** Vertices a simulation will hold (ps_sim_def.pinned_vertices): vertex group 0, kept on
   *  every level at their rest positions. A multi-level simulation's pinned vertices must be
   *  exactly these. Nullable; borrowed during the create call only. */
  const int32_t* pinned_vertices;
  size_t num_pinned_vertices; /**< entries in pinned_vertices; default 0 */
  /** Several vertex groups instead of pinned_vertices (not both): per input vertex its group,
   *  −1 for none, the groups numbered 0, 1, ... without gaps. Each group keeps its rest
   *  positions on every level and no collapse joins two groups. A multi-level simulation's
   *  handle i must be exactly group i: ps_sim_def.pinned_vertices group 0, then
   *  ps_sim_add_handle() the next. Nullable; num_vertex_group_ids is then 0, else the mesh's
   *  vertex count; borrowed during the create call only. */
  const int32_t* vertex_group_ids;
  size_t num_vertex_group_ids; /**< entries in vertex_group_ids; default 0 */
  /** m, ≥ 0; default 0. Coarse levels never cross themselves; with a contact offset ξ (half
   *  the shell thickness a contact simulation will use), no collapse also brings a vertex and
   *  a face, or two edges, that share no vertex within 2ξ (what contact checks at a level's
   *  start). Scenes (ps_sim_create_from_scene*) set it from their thickness themselves. */
  double contact_offset;
  /** Solids (ps_hierarchy_create_solid*): each coarse level is tetrahedralized with tets and
   *  boundary faces about this many times its surface's mean edge length (m/m), in (0, 100];
   *  default 0.6 (tets about as long as the surface's edges). Shells ignore it. */
  double tet_size_factor;
  /** Solids from a closed surface (ps_hierarchy_create_solid_from_surface, or a surface file):
   *  the largest tet circumradius of the finest level, m; 0 (default): the surface's
   *  bounding-box diagonal / 20. The tets' count grows like (size / tet_cell_size)³. */
  double tet_cell_size;
  int32_t internal_cookie; /**< set by ps_hierarchy_def_init(); do not touch */
} ps_hierarchy_def;

/** Fills def with defaults (single level). def must not be NULL. */
PS_API void ps_hierarchy_def_init(ps_hierarchy_def* def);

/**
 * Builds a hierarchy from a triangle mesh. The mesh is validated first (NaN/Inf
 * coordinates, out-of-range indices, degenerate faces, non-manifold edges, unreferenced
 * vertices → PS_ERROR_INVALID_MESH naming the first offender). Coarse levels come from
 * quadric edge collapse with probabilistic quadrics (PSQ §4.1), each with the intrinsic map
 * and shell prolongation to the finest level (PSQ §4.3) and its expansion batches (§4.4.4).
 * Vertex counts must be distinct, at least 4 and below the mesh's (PS_ERROR_INVALID_ARGUMENT);
 * a surface that cannot be decimated that far while staying valid gives
 * PS_ERROR_INVALID_MESH saying where decimation stopped.
 * @param def          Nullable (defaults). Borrowed during the call.
 * @param vertices     (num_vertices × 3) positions, m. Copied.
 * @param faces        (num_faces × 3) vertex indices. Copied.
 * @param out          receives the new hierarchy; caller owns, destroy with
 *                     ps_hierarchy_destroy(). Unchanged on failure.
 */
PS_API int32_t ps_hierarchy_create(const ps_hierarchy_def* def, const double* vertices,
                                   size_t num_vertices, const int32_t* faces, size_t num_faces,
                                   ps_hierarchy** out);

/** As ps_hierarchy_create(), reading the mesh from an OBJ, OFF or PLY file at `path`
 *  (format from the extension; triangles only). A file that cannot be read or parsed gives
 *  PS_ERROR_IO, including PLY files with non-float coordinates or list counts wider than
 *  16 bits; non-triangle faces or out-of-range indices give PS_ERROR_INVALID_MESH. */
PS_API int32_t ps_hierarchy_create_from_file(const ps_hierarchy_def* def, const char* path,
                                             ps_hierarchy** out);

/** Destroys a hierarchy. Nullable (no-op, PS_OK). While simulations created on it with
 *  ps_sim_create() exist, the hierarchy is kept and the call returns
 *  PS_ERROR_WRONG_CALL_ORDER (message in ps_last_error()): destroy them first. */
PS_API int32_t ps_hierarchy_destroy(ps_hierarchy* hierarchy);

/** Message of the last failed call on this hierarchy ("" if none). Borrowed until the next
 *  call on it. A NULL hierarchy gives ps_last_error(). */
PS_API const char* ps_hierarchy_last_error(const ps_hierarchy* hierarchy);

/** Number of levels (≥ 1) into *out. */
PS_API int32_t ps_hierarchy_num_levels(const ps_hierarchy* hierarchy, int32_t* out);

/** Vertex and face counts of a level. Either out-pointer is nullable. */
PS_API int32_t ps_hierarchy_level_size(const ps_hierarchy* hierarchy, int32_t level,
                                       size_t* num_vertices, size_t* num_faces);

/** Rest positions of a level: (n × 3) doubles into out[capacity]; *count = 3n. out is
 *  nullable (size query). */
PS_API int32_t ps_hierarchy_get_rest_positions(const ps_hierarchy* hierarchy, int32_t level,
                                               double* out, size_t capacity, size_t* count);

/** Faces of a level: (m × 3) indices into out[capacity]; *count = 3m. out is nullable. */
PS_API int32_t ps_hierarchy_get_faces(const ps_hierarchy* hierarchy, int32_t level, int32_t* out,
                                      size_t capacity, size_t* count);

/**
 * Prolongs positions of `level` to the finest level with the shell prolongation
 * x = U x_l + a(x_l) (PSQ eq. 9): rigid motions of the coarse shape carry over exactly and the
 * rest shape of the level gives the finest rest shape. On a solid's hierarchy: the product of
 * the barycentric prolongations W of the levels above (VPD §3.3), which carries affine maps
 * of the coarse solid over exactly.
 * @param positions  (n_level × 3) doubles, m; count = 3 n_level. Borrowed.
 * @param out        (n_finest × 3) doubles into out[capacity]; *out_count = 3 n_finest.
 *                   Nullable (size query). The finest level copies positions through.
 */
PS_API int32_t ps_hierarchy_prolong(const ps_hierarchy* hierarchy, int32_t level,
                                    const double* positions, size_t count, double* out,
                                    size_t capacity, size_t* out_count);

/** Number of parallel vertex-split batches that refine `level` into level + 1 (PSQ §4.4.4)
 *  into *out. PS_ERROR_OUT_OF_RANGE for the finest level. */
PS_API int32_t ps_hierarchy_num_expansion_batches(const ps_hierarchy* hierarchy, int32_t level,
                                                  int32_t* out);

/** Saves the hierarchy to a file, so that decimation is paid once (progsim's binary
 *  hierarchy format; the CLI's `progsim hierarchy` writes the same). */
PS_API int32_t ps_hierarchy_save(const ps_hierarchy* hierarchy, const char* path);

/** Loads a hierarchy saved by ps_hierarchy_save(). A missing, truncated or corrupt file
 *  gives PS_ERROR_IO, PS_ERROR_INVALID_ARGUMENT or PS_ERROR_INVALID_MESH naming the path
 *  and the problem.
 *  @param out  receives the new hierarchy; caller owns (ps_hierarchy_destroy()). */
PS_API int32_t ps_hierarchy_load(const char* path, ps_hierarchy** out);

/* Solids (VPD §3.1.2). A solid's hierarchy holds a tet mesh per level: the finest is the user's,
 * each coarser one the tetrahedralization of its decimated boundary surface, and each finer
 * level's vertices are bound to the next coarser level's tets (barycentric weights, negative
 * for vertices outside it; VPD §3.3). Levels do not share vertices. The calls above read a
 * solid level's vertices (interior ones included) and its boundary faces over them;
 * ps_hierarchy_save(), ps_hierarchy_load() and ps_hierarchy_num_expansion_batches() apply to
 * shells only (PS_ERROR_UNSUPPORTED). A simulation on a solid's hierarchy of several levels
 * in PS_MODE_DYNAMIC is volumetric progressive dynamics (PS_SIM_VOLUMETRIC_DYNAMICS). */

/**
 * Builds a solid's hierarchy from a tet mesh. The mesh is validated first (NaN/Inf
 * coordinates, out-of-range indices, inverted or degenerate tets, duplicate tets, a boundary
 * that is not a closed manifold → PS_ERROR_INVALID_MESH naming the first offender). Coarse
 * levels: def->coarse_vertex_counts are the boundary vertex counts of the decimated surfaces
 * (distinct, at least 4 and below the finest boundary's); each is tetrahedralized with
 * def->tet_size_factor, which resamples the surface and adds interior vertices, so a coarse
 * level's vertex count (ps_hierarchy_num_vertices) differs from the count asked for.
 * def->pinned_vertices and def->contact_offset do not apply to solids' coarse levels. Progress
 * phases: "decimation", "tetrahedralization", "binding".
 * @param def       Nullable (defaults: one level). Borrowed during the call.
 * @param vertices  (num_vertices × 3) positions, m. Copied.
 * @param tets      (num_tets × 4) vertex indices, each tet positively oriented
 *                  ((x1 − x0)·((x2 − x0) × (x3 − x0)) > 0). Copied.
 * @param out       receives the new hierarchy; destroy with ps_hierarchy_destroy().
 */
PS_API int32_t ps_hierarchy_create_solid(const ps_hierarchy_def* def, const double* vertices,
                                         size_t num_vertices, const int32_t* tets, size_t num_tets,
                                         ps_hierarchy** out);

/**
 * As ps_hierarchy_create_solid(), the finest level being the solid a closed triangle surface
 * bounds, tetrahedralized by CGAL Mesh_3 with def->tet_cell_size (the boundary then lies on
 * the surface, its vertices resampled). A surface that is not valid, not closed or that
 * intersects itself gives PS_ERROR_INVALID_MESH naming the problem.
 */
PS_API int32_t ps_hierarchy_create_solid_from_surface(const ps_hierarchy_def* def,
                                                      const double* vertices, size_t num_vertices,
                                                      const int32_t* faces, size_t num_faces,
                                                      ps_hierarchy** out);

/** As ps_hierarchy_create_solid() from a tet mesh file (Medit .mesh, Gmsh .msh v2/v4 ASCII,
 *  TetGen .node/.ele), or as ps_hierarchy_create_solid_from_surface() from a closed surface
 *  file (.obj, .off, .ply); the format from the extension. Unreadable files: PS_ERROR_IO. */
PS_API int32_t ps_hierarchy_create_solid_from_file(const ps_hierarchy_def* def, const char* path,
                                                   ps_hierarchy** out);

/** 1 into *out for a solid's (tet) hierarchy, 0 for a shell's. */
PS_API int32_t ps_hierarchy_is_solid(const ps_hierarchy* hierarchy, int32_t* out);

/** Tets of a solid's level: (k × 4) indices into the level's vertices into out[capacity];
 *  *count = 4k. out is nullable (size query). A shell's hierarchy has none: *count = 0. */
PS_API int32_t ps_hierarchy_get_tets(const ps_hierarchy* hierarchy, int32_t level, int32_t* out,
                                     size_t capacity, size_t* count);

/* ---------------------------------------------------------------- simulation ----------- */

/** A simulation of one hierarchy: preview steps at the current level, then refinement. */
typedef struct ps_sim ps_sim;

/** How steps advance. */
typedef enum ps_mode {
  PS_MODE_DYNAMIC = 0,     /**< implicit Euler with inertia */
  PS_MODE_QUASISTATIC = 1, /**< each step minimises the potential energy at its loads */
  PS_MODE_FORCE32 = 0x7fffffff
} ps_mode;

/** How a finer level of a progressive animation (PS_SIM_PROGRESSIVE_DYNAMICS) predicts each
 *  step, the x̂ of its incremental potential, from the coarser level's trajectory (x_l^t, v_l^t
 *  the coarser frame t, U the intrinsic part of the prolongation P); scene key
 *  "progressive.prediction". */
typedef enum ps_prediction {
  /** PD++'s velocity-only prolongation (the default): x̂ = x_{l+1}^t + h U v_l^t, the level's
   *  own positions moved by the coarser velocity; temporally smooth. */
  PS_PREDICTION_VELOCITY_ONLY = 0,
  /** PD eq. 5: x̂ = P(x_l^t) + h U v_l^t; resets the fine positions toward the coarse ones every
   *  step (closer to the preview, can jump between frames). */
  PS_PREDICTION_PROLONGED_POSITIONS = 1,
  /** PSQ per frame, for comparison: x̂ = P(x_l^{t+1}), each step a relaxation toward the
   *  prolonged coarser frame with no inertia of its own. */
  PS_PREDICTION_PER_FRAME = 2,
  PS_PREDICTION_FORCE32 = 0x7fffffff
} ps_prediction;

/** How keyframed motion (ps_sim_set_handle_keyframes()) moves between two keys, s ∈ [0, 1)
 *  the time since the earlier key over the segment's duration; scene key
 *  "motion.interpolation". */
typedef enum ps_interpolation {
  PS_INTERPOLATION_HOLD = 0,   /**< a step: the earlier key's pose until the next key's time */
  PS_INTERPOLATION_LINEAR = 1, /**< uniformly in time (weight s) */
  PS_INTERPOLATION_SMOOTH = 2, /**< smoothstep 3s² − 2s³: zero velocity at every key */
  PS_INTERPOLATION_FORCE32 = 0x7fffffff
} ps_interpolation;

/** Physical effects; only enabled effects cost anything. Combine with |. */
typedef enum ps_effect {
  PS_EFFECT_MEMBRANE = 1 << 0,     /**< Neo-Hookean membrane stretching */
  PS_EFFECT_BENDING = 1 << 1,      /**< discrete hinge bending */
  PS_EFFECT_GRAVITY = 1 << 2,      /**< uniform gravity */
  PS_EFFECT_PRESSURE = 1 << 3,     /**< uniform inner pressure of closed meshes */
  PS_EFFECT_CONTACT = 1 << 4,      /**< IPC barrier self-contact with CCD; intersection-free */
  PS_EFFECT_FRICTION = 1 << 5,     /**< Coulomb friction on contacts (with material_friction > 0) */
  PS_EFFECT_STRAIN_LIMIT = 1 << 6, /**< barrier keeping stretches below material_strain_limit */
  PS_EFFECT_WIND = 1 << 7,         /**< aerodynamic drag and lift of ps_sim_def's wind (dynamic) */
  PS_EFFECT_ELASTICITY = 1 << 8,   /**< hyperelastic energy of volumetric (tetrahedral) bodies */
  PS_EFFECT_FORCE32 = 0x7fffffff
} ps_effect;

/**
 * A simulation described in code. Fill with ps_sim_def_init(). The numeric fields are the
 * parameter table's rows (core/scene/parameters.def; `progsim params` prints it): field
 * group_name is parameter group.name, written here by scripts/generate_c_parameters.py, which a
 * test runs to check that the header matches the table.
 */
typedef struct ps_sim_def {
  /* BEGIN fields generated from core/scene/parameters.def by scripts/generate_c_parameters.py */
  /** Time step h of implicit Euler (dynamic) or the load-step length (quasistatic). Unit s,
   * range (0, 100]; default 0.01. */
  double simulation_time_step;
  /** Simulated time; the run takes round(duration / time_step) steps. Unit s, range (0, 1e7];
   * default 1. */
  double simulation_duration;
  /** Write a mesh every this many steps (the last step is always written). Unit steps, range [1,
   * 1000000000]; default 1. */
  int32_t simulation_output_every;
  /** Gravity grows linearly from 0 to its full value over this time, like a body's pressure_ramp
   * (quasistatic self-weight in load steps); 0: full gravity from the start. Unit s, range [0,
   * 1e7]; default 0. */
  double simulation_gravity_ramp;
  /** Young's modulus E of the shell material. Unit Pa, range (0, 1e13]; default 1e6. */
  double material_youngs_modulus;
  /** Young's modulus of the bending term alone (cloth often bends stiffer or softer than it
   * stretches; PSQ's tables give E_mem and E_bend); 0: youngs_modulus. Unit Pa, range [0, 1e13];
   * default 0. */
  double material_bending_youngs_modulus;
  /** Poisson ratio nu; must lie in (-1, 0.5). Unit 1, range (-1, 0.5); default 0.3. */
  double material_poisson_ratio;
  /** Shell thickness t (membrane energy scales with t, bending with t^3). Unit m, range (0, 10];
   * default 0.001. */
  double material_thickness;
  /** Volumetric density rho; the areal density is rho * t. Unit kg/m^3, range (0, 1e6]; default
   * 200. */
  double material_density;
  /** Coulomb friction coefficient mu of the surface; a pair uses sqrt(mu_a * mu_b). 0:
   * frictionless. Unit 1, range [0, 10]; default 0. */
  double material_friction;
  /** Largest principal membrane stretch s_max (> 1, e.g. 1.06), kept by a barrier; 0: no limit.
   * Unit 1, range [0, 100]; default 0. */
  double material_strain_limit;
  /** Contact activation gap d-hat: the barrier acts on primitive pairs closer than this. Unit m,
   * range (0, 10]; default 0.001. */
  double contact_dhat;
  /** Barrier stiffness kappa on squared distances; 0: chosen from the loads and grown
   * adaptively. Unit N/m^3, range [0, 1e30]; default 0. */
  double contact_stiffness;
  /** Friction smoothing speed eps_v: slips slower than this are treated as sticking. Unit m/s,
   * range (0, 1000]; default 0.001. */
  double contact_friction_velocity;
  /** 1: a progressive run may start from a finest rest shape that crosses itself or an obstacle
   * (its coarse levels must not); safe refinement separates it level by level and the summary
   * counts the input's crossing face pairs. 0: such a scene is refused, naming a crossing pair.
   * Direct runs always refuse it. Unit 1, range [0, 1]; default 0. */
  int32_t contact_crossing_start;
  /** Density rho of the air the wind blows (1.2: air at 20 C). Unit kg/m^3, range (0, 10000];
   * default 1.2. */
  double wind_density;
  /** Drag coefficient C_d of each face: normal force 1/2 rho C_d A abs(u.n) (u.n) n from the
   * relative wind u (about 1.2 for a flat plate across a flow); 0: no drag. Unit 1, range [0,
   * 100]; default 1.2. */
  double wind_drag;
  /** Lift coefficient C_L of each face: force 1/2 rho C_L A u^2 cos(a) sin(a) across u in the
   * plane of u and the normal n (a: the angle of u and n); 0: no lift. Unit 1, range [0, 100];
   * default 0. */
  double wind_lift;
  /** Newton stops when |p|_inf / s < tolerance * bbox diagonal (s = h for dynamics, 1 for
   * quasistatics). Unit 1, range (0, 1]; default 1e-5. */
  double solver_newton_tolerance;
  /** Cap on Newton iterations per step; hitting it is reported, not an error. Unit 1, range [1,
   * 1000000]; default 100. */
  int32_t solver_max_newton_iterations;
  /** CG iterations refining each projected Newton step against the exact Hessian
   * (Steihaug-Toint, trust region; not in PSQ proxy solves); 0: off. Unit 1, range [0, 1000000];
   * default 0. */
  int32_t solver_max_cg_iterations;
  /** 1: a whole Newton step whose energy fell much more than predicted is lengthened, doubling
   * alpha while the energy falls and CCD allows (Nocedal & Wright 3.5); 0: off, for comparison
   * runs. Unit 1, range [0, 1]; default 1. */
  int32_t solver_line_search_extrapolation;
  /** PSQ: Newton iterations per preview step on a coarse level (PSQ 4.5, Algorithm 1); dynamic
   * previews solve each step to the tolerance instead. Unit 1, range [1, 1000000]; default 8. */
  int32_t progressive_preview_iterations;
  /** Tolerance of preview solves, for their Newton steps and for when a preview level is at rest
   * (PSQ Algorithm 1 line 10); 0: solver.newton_tolerance. Unit 1, range [0, 1]; default 0. */
  double progressive_preview_tolerance;
  /** 1: quasistatic steps add PSQ eq. 1's proximal term 1/(2h^2) |x - x_t|^2_M on every level
   * and in the direct baseline, a gradient flow that keeps the Newton matrix definite for free
   * bodies (a cloth dropped on a sphere); 0: off. Unit 1, range [0, 1]; default 0. */
  int32_t progressive_proximal;
  /** Dynamic scenes with the Galerkin proxy Hessian: it is reassembled once the finest state has
   * moved, net of its mean translation, by more than this many mean finest edge lengths at some
   * vertex since the last assembly (the proxy's gradient stays exact; a chord method; a Newton
   * step longer than 0.8 of the previous one also reassembles it); 0: every Newton iteration, as
   * quasistatic previews always do. Unit 1, range [0, 1e6]; default 0.5. */
  double progressive_galerkin_refresh;
  /** Progressive Dynamics: weight w of the consistency penalty (VPD eq. 4, from PD++), w/(2h^2)
   * times the squared mass norm of x - P(x_coarser), pulling each finer level toward the
   * prolonged coarser frame (w = 1 weighs it like the inertia); 0: no penalty term. Unit 1,
   * range [0, 1e12]; default 0. */
  double progressive_consistency_weight;
  /* END generated fields */
  ps_mode mode; /**< default PS_MODE_DYNAMIC */
  /** a progressive animation's prediction; default PS_PREDICTION_VELOCITY_ONLY */
  ps_prediction prediction;
  uint32_t effects;  /**< ps_effect bits; default membrane|bending|gravity */
  double gravity[3]; /**< m/s²; default (0, −9.81, 0) */
  double pressure;   /**< Pa, needs PS_EFFECT_PRESSURE; default 0 */
  /** Finest-level vertices held still (handle 0). Nullable; borrowed during create. */
  const int32_t* pinned_vertices;
  size_t num_pinned_vertices; /**< entries in pinned_vertices; default 0 */
  int32_t internal_cookie;    /**< set by ps_sim_def_init(); do not touch */
  /** The wind (PS_EFFECT_WIND; dynamic only, with wind_density, wind_drag and wind_lift above):
   *  m/s; default (0, 0, 0): still air, drag only (scenes/README.md, "Wind"). */
  double wind_velocity[3];
  /** Gusts: num_wind_keyframes rows (time s, vx, vy, vz m/s), times increasing, the wind linear
   *  between them and held outside them; they replace wind_velocity. Nullable; borrowed during
   *  create. */
  const double* wind_keyframes;
  size_t num_wind_keyframes; /**< rows in wind_keyframes; default 0 */
} ps_sim_def;

/** Fills def with the defaults above. def must not be NULL. */
PS_API void ps_sim_def_init(ps_sim_def* def);

/**
 * Creates a simulation of `hierarchy` (borrowed: it must outlive the simulation) as
 * described by `def` (nullable: defaults). Starts at level 0 at rest. Its kind follows from
 * the hierarchy and the mode (see ps_sim_kind): one level gives a direct simulation; several
 * levels give Progressive Dynamics in PS_MODE_DYNAMIC (the default: a progressive animation)
 * and PSQ in PS_MODE_QUASISTATIC. On several levels the pinned vertices must be the
 * hierarchy's (ps_hierarchy_def.pinned_vertices; otherwise PS_ERROR_INVALID_ARGUMENT).
 * On a solid's hierarchy the body is the finest tet mesh (material_* its Young's modulus,
 * Poisson ratio and density; choice "material.solid_model" its energy) and its effects must
 * include PS_EFFECT_ELASTICITY and no shell effect (membrane, bending, pressure, strain limit,
 * wind: PS_ERROR_INVALID_SCENE naming it); a NULL def gives elasticity and gravity. Several
 * levels animate it with VPD in PS_MODE_DYNAMIC; PS_MODE_QUASISTATIC needs one level
 * (PS_ERROR_UNSUPPORTED), as do pinned vertices (they index the finest level, which coarse tet
 * levels do not share: hold vertices on every VPD level by box, ps_sim_add_handle_box()).
 * @param out receives the simulation; caller owns, destroy with ps_sim_destroy().
 * Errors: PS_ERROR_UNINITIALIZED_DEF, PS_ERROR_INVALID_ARGUMENT (a parameter NaN or out of
 * its range, a prediction that is not a ps_prediction, naming it), PS_ERROR_INVALID_SCENE (a
 * pinned vertex out of range; quasistatic, a body that gravity or pressure on an open surface
 * pulls with no pin, no ground or obstacle under contact and no proximal term to hold it,
 * naming it), PS_ERROR_NULL_ARGUMENT.
 */
PS_API int32_t ps_sim_create(const ps_hierarchy* hierarchy, const ps_sim_def* def, ps_sim** out);

/**
 * Creates a simulation from a JSON scene (format: scenes/README.md). Its bodies' meshes form
 * the hierarchy, which the simulation owns (see ps_sim_hierarchy()). A dynamic scene with a
 * "progressive" section of coarse levels gives a progressive animation (Progressive Dynamics;
 * its "prediction" and "consistency_weight" apply; VPD for a volumetric body, whose hierarchy
 * is then a solid's), a quasistatic one PSQ, a scene without coarse levels a direct
 * simulation.
 * @param json     NUL-terminated scene text. Borrowed during the call.
 * @param base_dir Nullable: directory that relative mesh paths in the scene start from
 *                 (NULL: the current directory).
 * Errors: PS_ERROR_INVALID_SCENE with the JSON path of the problem (unknown key, missing
 * field, value out of range), PS_ERROR_INVALID_MESH, PS_ERROR_IO.
 */
PS_API int32_t ps_sim_create_from_scene(const char* json, const char* base_dir, ps_sim** out);

/** As ps_sim_create_from_scene(), reading the scene from a file; relative mesh paths start
 *  from the file's directory. */
PS_API int32_t ps_sim_create_from_scene_file(const char* path, ps_sim** out);

/** Destroys a simulation (and the hierarchy it owns, if any). Nullable (no-op). */
PS_API void ps_sim_destroy(ps_sim* sim);

/** Message of the last failed call on this simulation ("" if none). Borrowed until the next
 *  call on it. A NULL sim gives ps_last_error(). */
PS_API const char* ps_sim_last_error(const ps_sim* sim);

/** The hierarchy this simulation runs on. Borrowed until ps_sim_destroy(). Calls on it
 *  store their error message in it, so it belongs to the thread that uses the simulation. */
PS_API int32_t ps_sim_hierarchy(const ps_sim* sim, const ps_hierarchy** out);

/** What drives a simulation; it follows from the hierarchy's levels and the mode at creation
 *  and does not change. */
typedef enum ps_sim_kind {
  PS_SIM_DIRECT = 0, /**< one level: implicit Euler or quasistatic load steps on the mesh */
  PS_SIM_PSQ = 1,    /**< several levels, quasistatic: Progressive Shell Quasistatics */
  /** several levels, dynamic: Progressive Dynamics, a progressive animation (frames per level,
   *  see "progressive animation" below) */
  PS_SIM_PROGRESSIVE_DYNAMICS = 2,
  /** a solid's hierarchy of several levels, dynamic: volumetric progressive dynamics (VPD), a
   *  progressive animation over tet levels, each with its own elastics */
  PS_SIM_VOLUMETRIC_DYNAMICS = 3,
  PS_SIM_KIND_FORCE32 = 0x7fffffff
} ps_sim_kind;

/** The simulation's kind (a ps_sim_kind) into *out. */
PS_API int32_t ps_sim_get_kind(const ps_sim* sim, int32_t* out);

/** Installs (or with fn = NULL removes) the progress callback. user_data is passed back
 *  unchanged (borrowed; the caller keeps it alive while installed). */
PS_API int32_t ps_sim_set_progress_callback(ps_sim* sim, ps_progress_fn fn, void* user_data);

/**
 * Sets a numeric parameter by name between steps: any parameter-table name
 * ("material.youngs_modulus", "simulation.time_step", "solver.newton_tolerance",
 * "progressive.consistency_weight", ...) or "gravity.x", "gravity.y", "gravity.z" (m/s²),
 * "pressure" (Pa, all bodies).
 * Errors: PS_ERROR_INVALID_ARGUMENT for an unknown name (the message lists the known ones)
 * or a value outside the parameter's range (NaN included); the simulation is unchanged.
 * A progressive animation takes a change for its preview only: PS_ERROR_WRONG_CALL_ORDER once
 * a finer level has been computed (ps_sim_restart() first), PS_ERROR_INVALID_ARGUMENT for
 * "simulation.time_step" (fixed within an animation).
 */
PS_API int32_t ps_sim_set_param(ps_sim* sim, const char* name, double value);

/** Reads a parameter by name (names as in ps_sim_set_param()) into *out. */
PS_API int32_t ps_sim_get_param(const ps_sim* sim, const char* name, double* out);

/** Description of one parameter ps_sim_set_param() accepts. Strings are static. */
typedef struct ps_param_info {
  const char* name;     /**< e.g. "material.thickness" */
  const char* unit;     /**< SI unit, e.g. "m", "Pa", "1" */
  const char* doc;      /**< one-sentence description */
  double default_value; /**< the value ps_sim_def_init() sets */
  double min;           /**< admissible range [min, max] or (min, max), see below */
  double max;
  int32_t min_inclusive; /**< 1 if min itself is admissible */
  int32_t max_inclusive; /**< 1 if max itself is admissible */
  int32_t integer;       /**< 1 if only whole numbers are admissible */
} ps_param_info;

/** Number of parameters ps_sim_set_param() accepts. Thread-safe. */
PS_API int32_t ps_param_count(void);

/** Description of parameter `index` in [0, ps_param_count()) into *out. Thread-safe.
 *  Errors: PS_ERROR_OUT_OF_RANGE, PS_ERROR_NULL_ARGUMENT (messages in ps_last_error()). */
PS_API int32_t ps_param_info_get(int32_t index, ps_param_info* out);

/** Description of one named option ps_sim_set_choice() accepts (the choice table; scene keys
 *  of the same names). Strings are static. */
typedef struct ps_choice_info {
  const char* name;           /**< e.g. "progressive.prolongation" */
  const char* options;        /**< the admissible values separated by '|', e.g. "composed|direct" */
  const char* default_option; /**< one of them: what a new simulation uses */
  const char* doc;            /**< one-sentence description */
} ps_choice_info;

/** Number of named options ps_sim_set_choice() accepts. Thread-safe. */
PS_API int32_t ps_choice_count(void);

/** Description of named option `index` in [0, ps_choice_count()) into *out. Thread-safe.
 *  Errors: PS_ERROR_OUT_OF_RANGE, PS_ERROR_NULL_ARGUMENT (messages in ps_last_error()). */
PS_API int32_t ps_choice_info_get(int32_t index, ps_choice_info* out);

/**
 * Sets named option `name` (ps_choice_info_get(), e.g. "progressive.proxy_hessian") to
 * `value`, one of its options (e.g. "galerkin"); material options apply to every body. Before
 * the first step, settle or refinement the simulation is rebuilt with it (its kind follows
 * "simulation.mode"; initial velocities set by ps_sim_set_preview_velocities() are kept);
 * later it is applied between steps like ps_sim_set_param(), where "progressive.prolongation"
 * takes effect from the next level on and "simulation.mode" behaves as ps_sim_set_mode().
 * Errors: PS_ERROR_NULL_ARGUMENT, PS_ERROR_INVALID_ARGUMENT (an unknown name or value: the
 * message lists the known ones), those of ps_sim_create() for the rebuilt simulation; on
 * error nothing changed.
 */
PS_API int32_t ps_sim_set_choice(ps_sim* sim, const char* name, const char* value);

/** The value of named option `name` into *out (a static string; material options: the
 *  first body's). Errors: PS_ERROR_NULL_ARGUMENT, PS_ERROR_INVALID_ARGUMENT (unknown name). */
PS_API int32_t ps_sim_get_choice(const ps_sim* sim, const char* name, const char** out);

/** Switches between dynamic and quasistatic stepping (a ps_mode) between steps; velocities
 *  are zeroed when switching to quasistatic. The simulation keeps its ps_sim_kind: a direct
 *  simulation switches either way, a PSQ simulation refuses PS_MODE_DYNAMIC
 *  (PS_ERROR_UNSUPPORTED) and a progressive animation PS_MODE_QUASISTATIC
 *  (PS_ERROR_INVALID_SCENE); create a new simulation in the other mode instead. Errors:
 *  PS_ERROR_INVALID_ARGUMENT; PS_ERROR_INVALID_SCENE for quasistatic with a body nothing holds
 *  (as ps_sim_create); those above. On error nothing changed. */
PS_API int32_t ps_sim_set_mode(ps_sim* sim, int32_t mode);

/** The stepping mode (a ps_mode) into *out. */
PS_API int32_t ps_sim_get_mode(const ps_sim* sim, int32_t* out);

/** Sets how a progressive animation's finer levels predict their steps (a ps_prediction), as
 *  ps_sim_set_param() sets numbers: refine() uses it from then on. Any kind of simulation
 *  stores it. Errors: PS_ERROR_INVALID_ARGUMENT (not a ps_prediction); on a progressive
 *  animation PS_ERROR_WRONG_CALL_ORDER once a finer level has been computed
 *  (ps_sim_restart() first). */
PS_API int32_t ps_sim_set_prediction(ps_sim* sim, int32_t prediction);

/** The prediction (a ps_prediction) into *out. */
PS_API int32_t ps_sim_get_prediction(const ps_sim* sim, int32_t* out);

/** Enables or disables one effect (a ps_effect bit) between steps. */
PS_API int32_t ps_sim_set_effect(ps_sim* sim, uint32_t effect, int32_t enabled);

/** The enabled effects (ps_effect bits) into *out. */
PS_API int32_t ps_sim_get_effects(const ps_sim* sim, uint32_t* out);

/** How a load's force is spread over its vertex group (scene key "distribution"). */
typedef enum ps_load_distribution {
  PS_LOAD_BY_MASS = 0,    /**< f_i = F m_i / Σ m_j, m the lumped vertex masses (the default) */
  PS_LOAD_BY_AREA = 1,    /**< f_i = F A_i / Σ A_j, A a third of each incident face's area */
  PS_LOAD_PER_VERTEX = 2, /**< f_i = F on every vertex of the group */
  PS_LOAD_DISTRIBUTION_FORCE32 = 0x7fffffff
} ps_load_distribution;

/**
 * A point or line load on a vertex group (scene key "loads"), grown linearly from 0 over `ramp`:
 * a force and a moment fixed in direction and size (potential −Σ f_i·x_i), and a normal force
 * that follows the surface (any of them together).
 * Fill with ps_load_def_init(), then change fields.
 */
typedef struct ps_load_def {
  int32_t body; /**< index of the scene's body (0 for ps_sim_create); default 0 */
  /** The group: vertex indices within the body's mesh (each counted once). Required;
   *  borrowed during ps_sim_add_load() only. */
  const int32_t* vertices;
  size_t num_vertices; /**< entries in vertices; default 0 */
  double force[3];     /**< N: the total, or on each vertex with PS_LOAD_PER_VERTEX; default 0 */
  ps_load_distribution distribution; /**< default PS_LOAD_BY_MASS */
  /** Direction of the moment (any length > 0); default (0, 0, 1) */
  double moment_axis[3];
  /** N·m; default 0 (none): a couple of forces on the group, weighted like the force (equally
   *  with PS_LOAD_PER_VERTEX), summing to zero, with moment `moment` about moment_axis. The
   *  group must not lie on one line along the axis. */
  double moment;
  /** N along the unit vertex normals (the faces' winding), spread like the force, turning with
   *  the surface: a follower load, re-aimed and solved again each step until its directions
   *  hold still. Single-level simulations only. Default 0 (none). */
  double normal_force;
  double ramp; /**< s, ≥ 0; default 0 (full load at once) */
  /** The group as a region instead (with num_vertices = 0): the body's vertices inside the
   *  axis-aligned box [box_min, box_max] (m, boundary included), each NULL or 3 doubles,
   *  both set or neither; borrowed during ps_sim_add_load() only. On VPD levels, which share
   *  no vertices, each level takes its own vertices inside it. Default NULL. */
  const double* box_min;
  const double* box_max;   /**< see box_min; default NULL */
  int32_t internal_cookie; /**< set by ps_load_def_init(); do not touch */
} ps_load_def;

/** Fills def with the defaults above. def must not be NULL. */
PS_API void ps_load_def_init(ps_load_def* def);

/**
 * Adds a load from the next step on (from its ramp's start: the load at time t is
 * min(1, t / ramp) of its full value, t the simulated time). Direct simulations apply it on
 * their level; progressive ones on the finest level's vertices, through the prolongation on
 * coarse levels (PSQ eq. 2). Its counters are the term "loads" in the step records.
 * @param out_index Nullable: receives the load's index (0, 1, ... in order of addition).
 * Errors: PS_ERROR_UNINITIALIZED_DEF, PS_ERROR_NULL_ARGUMENT (def, or vertices with
 * num_vertices > 0), PS_ERROR_INVALID_ARGUMENT (a distribution that is not a
 * ps_load_distribution; one box corner without the other, a box with vertices too, a
 * non-finite corner or box_min above box_max), PS_ERROR_INVALID_SCENE naming the load and the
 * problem (no vertices, a box that holds none, a vertex or body out of range, a non-finite
 * value, a zero moment axis, a negative ramp, a group that cannot carry the moment). On error
 * nothing changed.
 */
PS_API int32_t ps_sim_add_load(ps_sim* sim, const ps_load_def* def, int32_t* out_index);

/** Number of loads (ps_sim_add_load() and the scene's "loads") into *out. */
PS_API int32_t ps_sim_num_loads(const ps_sim* sim, int32_t* out);

/** Number of handles (scripted vertex groups) into *out. */
PS_API int32_t ps_sim_num_handles(const ps_sim* sim, int32_t* out);

/**
 * Scripts handle `handle` from the next step on: its vertices follow
 * x(t) = c + R(ω t)(x̄ − c) + v t + offset, t the simulated time, x̄ the rest position,
 * R the rotation about unit `axis` through `center` (m) at `angular_velocity` (rad/s),
 * v = `velocity` (m/s) and `offset` (m) a translation a designer can drag. Any vector
 * argument is nullable (zero; axis defaults to +z). Replaces keyframes
 * (ps_sim_set_handle_keyframes()). Errors: PS_ERROR_OUT_OF_RANGE (no such handle),
 * PS_ERROR_INVALID_ARGUMENT (a NaN/Inf value or a zero axis).
 */
PS_API int32_t ps_sim_set_handle_motion(ps_sim* sim, int32_t handle, const double velocity[3],
                                        const double axis[3], const double center[3],
                                        double angular_velocity, const double offset[3]);

/** The world coordinates a handle prescribes; combine with |. */
typedef enum ps_axis {
  PS_AXIS_X = 1 << 0,
  PS_AXIS_Y = 1 << 1,
  PS_AXIS_Z = 1 << 2,
  PS_AXIS_ALL = PS_AXIS_X | PS_AXIS_Y | PS_AXIS_Z, /**< a clamp (every handle's default) */
  PS_AXIS_FORCE32 = 0x7fffffff
} ps_axis;

/**
 * Makes handle `handle` prescribe only the coordinates in `axes` (ps_axis bits) from the next
 * step on; its vertices move freely along the others: a roller (e.g. PS_AXIS_Y: held in
 * height, free to slide in x and z) or a symmetry plane (the axis normal to it). Scene key
 * handles[i].axes. Errors: PS_ERROR_OUT_OF_RANGE (no such handle), PS_ERROR_INVALID_SCENE
 * (no axis, or bits other than PS_AXIS_ALL).
 */
PS_API int32_t ps_sim_set_handle_axes(ps_sim* sim, int32_t handle, uint32_t axes);

/** What a handle holds of its vertices (scene key handles[i].support). */
typedef enum ps_support {
  /** Each vertex's prescribed coordinates follow the script, the others are free per vertex
   *  (a clamp, a roller, a symmetry plane): "position", every handle's default. */
  PS_SUPPORT_POSITION = 0,
  /** The group moves rigidly: it turns as its script turns it (held still by a static script)
   *  and translates freely along the coordinates outside its axes, one translation for all its
   *  vertices: "rotation". Give it two or more rows of a shell's vertices to hold a slope (a
   *  guided clamp; an end turned with its position free). Single-level simulations only. */
  PS_SUPPORT_ROTATION = 1,
  PS_SUPPORT_FORCE32 = 0x7fffffff
} ps_support;

/**
 * Makes handle `handle` a `support` (a ps_support) prescribing the coordinates in `axes`
 * (ps_axis bits; 0 allowed only for PS_SUPPORT_ROTATION: a free translation) from the next step
 * on. Scene keys handles[i].support and handles[i].axes. Errors: PS_ERROR_OUT_OF_RANGE (no such
 * handle), PS_ERROR_INVALID_ARGUMENT (not a ps_support), PS_ERROR_INVALID_SCENE (axes 0 for a
 * position support, bits other than PS_AXIS_ALL), PS_ERROR_UNSUPPORTED (a rotation support on a
 * simulation of several levels); on error the handle is unchanged.
 */
PS_API int32_t ps_sim_set_handle_support(ps_sim* sim, int32_t handle, int32_t support,
                                         uint32_t axes);

/** The force and moment a handle's support applies to the shell. */
typedef struct ps_handle_reaction {
  double force[3];  /**< N, Σ over its vertices; 0 along the coordinates it leaves free */
  double moment[3]; /**< N·m, Σ (x_i − point) × R_i */
  double point[3];  /**< m, centroid of the handle's vertices */
} ps_handle_reaction;

/**
 * What handle `handle`'s support applied after the last solve on `level` (R = ∂E/∂x at the
 * prescribed coordinates, E the step's objective: in a quasistatic step it balances the
 * loads; in a dynamic one it also accelerates the handle's mass) into *out. In a progressive
 * animation: after the level's last computed step. Errors: PS_ERROR_OUT_OF_RANGE (no such
 * level or handle), PS_ERROR_WRONG_CALL_ORDER (no solve on the level yet, or it is a preview
 * level, whose proxy holds the finest handle vertices and reports no reaction).
 */
PS_API int32_t ps_sim_get_handle_reaction(const ps_sim* sim, int32_t level, int32_t handle,
                                          ps_handle_reaction* out);

/**
 * Scripts handle `handle` by keyframes from the next step on, replacing its motion: its
 * vertices follow x(t) = c + R(t)(x̄ − c) + T(t) + offset, t the simulated time (s), x̄ the rest
 * position, c and offset the centre and offset of the handle's current motion (from
 * ps_sim_set_handle_motion() or the scene; the origin and 0 by default), T(t) (m) and R(t)
 * interpolated between the keys by `interpolation` (a ps_interpolation): translations
 * componentwise; rotations about one axis (or with either angle 0) by their angle, so a segment may
 * turn several times, about different axes by quaternion slerp (the shorter arc). Before the first
 * key its pose, after the last held. The handle's velocity and angular velocity become 0 (keyframes
 * replace them).
 * @param rows      num_rows keys (num_rows × 8), row-major: time (s, strictly increasing),
 *                  translation tx, ty, tz (m), rotation axis ax, ay, az (non-zero, need not be
 *                  unit) and angle (rad, right-handed about the axis through c). Borrowed
 *                  during the call.
 * @param num_rows  at least 1.
 * Errors: PS_ERROR_OUT_OF_RANGE (no such handle), PS_ERROR_NULL_ARGUMENT (rows),
 * PS_ERROR_INVALID_ARGUMENT (num_rows = 0, not a ps_interpolation, a NaN/Inf value, a zero
 * axis, times not strictly increasing: the message names the key, e.g.
 * "handles[0].motion.keyframes[2].time"); on error the motion is unchanged.
 */
PS_API int32_t ps_sim_set_handle_keyframes(ps_sim* sim, int32_t handle, const double* rows,
                                           size_t num_rows, int32_t interpolation);

/**
 * Adds a handle (scene key "handles"): finest-level vertices `vertices` of body `body` (0 for
 * a simulation made by ps_sim_create()), held at rest until ps_sim_set_handle_motion() or
 * ps_sim_set_handle_keyframes() scripts them, prescribing all three coordinates until
 * ps_sim_set_handle_axes(). Its index (ps_sim_num_handles() − 1) goes to *out_index
 * (nullable). This rebuilds the simulation, so it is only allowed before its first step,
 * settle or refinement. On a hierarchy of several levels handle i must be the hierarchy's vertex
 * group i (ps_hierarchy_def.vertex_group_ids, or pinned_vertices for group 0 alone): after
 * ps_sim_def.pinned_vertices (group 0), each call adds the next group. Errors:
 * PS_ERROR_NULL_ARGUMENT (vertices NULL with num_vertices > 0), PS_ERROR_INVALID_SCENE (no vertex,
 * a body or vertex index out of range: the message names it), PS_ERROR_WRONG_CALL_ORDER (after a
 * step), PS_ERROR_INVALID_ARGUMENT (on several levels, vertices that are not a vertex group of the
 * hierarchy); on error nothing changed.
 */
PS_API int32_t ps_sim_add_handle(ps_sim* sim, int32_t body, const int32_t* vertices,
                                 size_t num_vertices, int32_t* out_index);

/**
 * Adds a handle of the vertices of body `body` inside the axis-aligned box [box_min, box_max]
 * (m, boundary included; scene key "handles" with a "box"), otherwise as ps_sim_add_handle().
 * On a solid's hierarchy of several levels (VPD) every level holds the vertices its box holds
 * there, since the levels share no vertices; a box that holds none on some level is
 * PS_ERROR_INVALID_SCENE naming the level. Errors: as ps_sim_add_handle(), and
 * PS_ERROR_INVALID_ARGUMENT for a non-finite corner or box_min above box_max on some axis,
 * PS_ERROR_INVALID_SCENE for a box that holds no vertex of the body; on error nothing changed.
 */
PS_API int32_t ps_sim_add_handle_box(ps_sim* sim, int32_t body, const double box_min[3],
                                     const double box_max[3], int32_t* out_index);

/** A collision object: a triangle mesh moved rigidly by a script, not simulated (scene key
 *  "obstacles"). Fill with ps_obstacle_def_init(), then set the mesh. */
typedef struct ps_obstacle_def {
  const double* vertices; /**< (num_vertices × 3) world positions at t = 0, m; borrowed */
  size_t num_vertices;    /**< at least 3 */
  const int32_t* faces;   /**< (num_faces × 3) vertex indices; borrowed */
  size_t num_faces;       /**< at least 1 */
  double friction;        /**< Coulomb μ of its surface, [0, 10]; default 0 */
  /** 0 (default) or 1: a progressive collision object (PSQ §4.6): coarse levels of a PSQ
   *  simulation meet a decimated copy, refined with the shell */
  int32_t progressive;
  int32_t internal_cookie; /**< set by ps_obstacle_def_init(); do not touch */
} ps_obstacle_def;

/** Fills def with the defaults above (no mesh). def must not be NULL. */
PS_API void ps_obstacle_def_init(ps_obstacle_def* def);

/**
 * Adds an obstacle, static until ps_sim_set_obstacle_motion() or
 * ps_sim_set_obstacle_keyframes() scripts it; its index goes to *out_index (nullable). Needs
 * PS_EFFECT_CONTACT. Like ps_sim_add_handle() it rebuilds the simulation, so only before the
 * first step. The mesh is validated (PS_ERROR_INVALID_MESH naming the first bad element);
 * an obstacle that crosses the shell at t = 0 or comes within its contact offset is refused
 * with PS_ERROR_INTERSECTING. Other errors: PS_ERROR_INVALID_SCENE (no contact effect,
 * friction out of range), PS_ERROR_WRONG_CALL_ORDER; on error nothing changed.
 */
PS_API int32_t ps_sim_add_obstacle(ps_sim* sim, const ps_obstacle_def* def, int32_t* out_index);

/** Number of obstacles into *out. */
PS_API int32_t ps_sim_num_obstacles(const ps_sim* sim, int32_t* out);

/** As ps_sim_set_handle_motion(), for obstacle `obstacle` (its vertices' rest positions are
 *  their positions at t = 0). Errors: PS_ERROR_OUT_OF_RANGE (no such obstacle),
 *  PS_ERROR_INVALID_ARGUMENT (a NaN/Inf value or a zero axis). */
PS_API int32_t ps_sim_set_obstacle_motion(ps_sim* sim, int32_t obstacle, const double velocity[3],
                                          const double axis[3], const double center[3],
                                          double angular_velocity, const double offset[3]);

/** As ps_sim_set_handle_keyframes(), for obstacle `obstacle`; messages name
 *  "obstacles[i].motion.keyframes[k]". */
PS_API int32_t ps_sim_set_obstacle_keyframes(ps_sim* sim, int32_t obstacle, const double* rows,
                                             size_t num_rows, int32_t interpolation);

/**
 * Sets the analytic ground (scene key "ground"): the half-space n·x ≥ height, a collision
 * object without a mesh; `enabled` 0 removes it. `normal` (nullable: +y) need not be unit,
 * `height` in m, `friction` Coulomb μ in [0, 10]. Needs PS_EFFECT_CONTACT to be enabled.
 * Allowed between steps: the shell must then be above the ground by its contact offset.
 * Errors: PS_ERROR_INVALID_ARGUMENT (NaN/Inf, a zero normal), PS_ERROR_INVALID_SCENE
 * (friction out of range, no contact effect), PS_ERROR_INTERSECTING (the shell is not
 * above it); on error nothing changed.
 */
PS_API int32_t ps_sim_set_ground(ps_sim* sim, int32_t enabled, const double normal[3],
                                 double height, double friction);

/**
 * Advances `steps` steps at the current level (the preview while it is not the finest).
 * Newton trouble does not fail the call: see the stats. Progress phase "preview".
 * A progressive animation animates its coarsest level, level 0 (PD eq. 4: each step solved to
 * the tolerance), appending one frame per step; once a finer level has been computed the
 * preview is closed (PS_ERROR_WRONG_CALL_ORDER, nothing changed) until ps_sim_restart().
 * Errors: PS_ERROR_INVALID_ARGUMENT (steps < 1), PS_ERROR_CANCELLED, PS_ERROR_NUMERICAL
 * (a step produced non-finite positions; the simulation keeps that step's state, so reading
 * positions shows the failure, and should be destroyed or its parameters changed),
 * PS_ERROR_WRONG_CALL_ORDER (above).
 */
PS_API int32_t ps_sim_step_preview(ps_sim* sim, int32_t steps);

/**
 * Refines the current level l to l + 1 toward the prolongation P^l_{l+1}(x_l) (PSQ eq. 7) at
 * the same time and loads, so that later steps run on the finer level. Below the finest level
 * steps are previews: the proxy energy (the finest level's elastics through the prolongation,
 * PSQ eq. 2) with few Newton iterations each. With contact the finer level is built by PSQ
 * §4.4's safe expansion: vertex splits batch by batch, each advanced toward P^l_{l+1}(x_l) only
 * as far as additive CCD allows, so it never starts intersecting even where the prolonged state
 * does; contact offsets and strain limits the start does not meet are relaxed to fit and
 * restored by the following solves. Progress phase "refine".
 * A progressive animation instead animates level l + 1 over every previewed step (PD eqs. 5–6,
 * Algorithm 1): its frame 0 is its rest shape with the prolonged initial velocities, and each
 * step's x̂ comes from level l's frames (ps_prediction) with the optional consistency penalty
 * (progressive_consistency_weight). Progress phase "refine" after each step (done, total = the
 * previewed steps); cancelling discards the level.
 * Errors (the state is unchanged): PS_ERROR_OUT_OF_RANGE at the finest level;
 * PS_ERROR_INTERSECTING when no safe position is found for a split;
 * PS_ERROR_NUMERICAL when the refined state has no finite energy; progressive animation:
 * PS_ERROR_WRONG_CALL_ORDER before any preview step, PS_ERROR_CANCELLED.
 */
PS_API int32_t ps_sim_refine(ps_sim* sim);

/**
 * Progressive animation only: animates the next level over the previewed steps first_step to
 * last_step only (0 <= first_step < last_step <= the previewed steps), so that time windows of
 * a long animation can be refined apart, on several machines, and joined. Its frame 0 is the
 * animation's frame first_step (ps_dynamic_level_stats.first_step): for first_step = 0 as
 * ps_sim_refine(), else the coarser level's frame first_step refined toward P(x) by PSQ's safe
 * refinement (PD §4.6's vertical warm start) with velocities U v, at that frame's time. The
 * steps then run as in ps_sim_refine(); a window of the whole span is ps_sim_refine(). A level
 * that is a window cannot be refined further. Progress phase "refine" (done, total = the
 * window's steps).
 * Errors (the state is unchanged): as ps_sim_refine(), and PS_ERROR_INVALID_ARGUMENT for a
 * window outside the previewed steps or a simulation that is not a progressive animation;
 * PS_ERROR_WRONG_CALL_ORDER above a level that is a window; PS_ERROR_UNSUPPORTED for a window
 * after frame 0 of a solid under contact (tets have no safe vertical refinement).
 */
PS_API int32_t ps_sim_refine_window(ps_sim* sim, int32_t first_step, int32_t last_step);

/**
 * Solves again at the current time and loads until the level is at equilibrium (a Newton
 * solve meets the tolerance with every face under its own strain limit) or `max_solves` solves
 * were made: after a refinement or a parameter change. *equilibrium (nullable) receives 1 if
 * reached, else 0. Progress phase "settle". Errors: PS_ERROR_INVALID_ARGUMENT (max_solves < 1,
 * or a progressive animation, whose levels are animations, not equilibria),
 * PS_ERROR_CANCELLED, PS_ERROR_NUMERICAL.
 */
PS_API int32_t ps_sim_settle(ps_sim* sim, int32_t max_solves, int32_t* equilibrium);

/** The current level into *out (0 = coarsest); for a progressive animation the finest level
 *  computed so far. */
PS_API int32_t ps_sim_current_level(const ps_sim* sim, int32_t* out);

/**
 * Positions of a level, (n × 3) doubles, into out[capacity]; *count = 3n. out is nullable
 * (size query). The current level gives the current state; a coarser level its state when
 * it was refined; a finer level the current state prolonged to it. A progressive animation
 * gives a computed level's last frame (ps_sim_get_frame_positions()).
 * Errors: PS_ERROR_OUT_OF_RANGE (a level that does not exist; progressive animation: one not
 * computed yet), PS_ERROR_BUFFER_TOO_SMALL.
 */
PS_API int32_t ps_sim_get_positions(const ps_sim* sim, int32_t level, double* out, size_t capacity,
                                    size_t* count);

/** Writes a level's current mesh (positions as ps_sim_get_positions(), faces of the level)
 *  to `path`; the extension picks the format (.obj, .off, .ply). */
PS_API int32_t ps_sim_write_mesh(const ps_sim* sim, int32_t level, const char* path);

/** How a level's start was built from the coarser level by safe refinement (PSQ §4.4);
 *  all zeros for level 0 and for scenes without contact (the prolonged state is used; its strain
 *  correction is in ps_strain_correction_stats). */
typedef struct ps_refinement_stats {
  int32_t batches;               /**< colour batches of vertex splits */
  int32_t splits;                /**< vertex splits over all batches */
  int32_t random_directions;     /**< splits whose target direction was unsafe (PSQ Alg. 5) */
  int32_t rounds;                /**< additive-CCD advancement rounds over all batches */
  int32_t stopped_vertices;      /**< moving vertices stopped by contact before their target */
  int32_t relaxed_vertices;      /**< stopped vertices relaxed locally (PSQ §4.4.3) */
  int32_t relaxation_iterations; /**< Newton iterations of those relaxations */
  int32_t inside_pairs; /**< contact pairs left within their offset, opened by later solves */
  /** 1 − Σ‖x̂ − x‖ / Σ‖x̂ − x₀‖ over the moving vertices: 1 when all reached the prolonged
   *  target x̂, 0 when none moved. */
  double reached;
  double min_gap; /**< smallest gap d − ξ of contact pairs outside their offsets, m */
} ps_refinement_stats;

/** How a refined start was brought under its strain limits (PSQ §4.4.5): the new vertices
 *  move, the coarser level's held, until every face is under its limit (the coarser vertices
 *  move too where that cannot be reached with them held). Zeros for level 0 and for scenes
 *  without strain limits. */
typedef struct ps_strain_correction_stats {
  int32_t strained_faces;        /**< faces at or beyond their strain limit before it */
  int32_t over_limit_faces;      /**< … after it (0: the start is strain-feasible) */
  int32_t newton_iterations;     /**< Newton iterations of the correction */
  int32_t moved_coarse_vertices; /**< 1 if the coarser level's vertices had to move too */
  double stretch_before;         /**< largest principal stretch of a limited face before it */
  double stretch_after;          /**< … after it */
} ps_strain_correction_stats;

/** Per-level statistics, accumulated over every step and settle at that level. */
typedef struct ps_level_stats {
  int32_t level;             /**< which level */
  int32_t steps;             /**< steps taken at this level */
  int32_t newton_iterations; /**< total Newton iterations (steps and settles) */
  int32_t converged_steps;   /**< steps and settles whose Newton solve met the tolerance */
  double seconds;            /**< wall time solving at this level, s */
  double energy;             /**< incremental potential after the last step, J */
  double gradient_norm;      /**< ‖∇E‖ over free DOFs after the last step, N */
  double simulated_time;     /**< simulated time reached, s */
  /** RMS / max vertex distance of the level's state (prolonged to the finest mesh) to the
   *  converged finest solution, over the finest bounding-box diagonal; NaN until the finest
   *  level is at equilibrium (ps_sim_settle() there). */
  double error_rms;
  double error_max;
  int32_t settles;       /**< solves at a fixed time (ps_sim_settle()) */
  int32_t equilibrium;   /**< 1 if the last solve left an equilibrium (quasistatic: tolerance met
                          *  with the scripts arrived, before any Newton step with the proximal
                          *  term, no strain limit still raised); 0 for dynamic scenes */
  double refine_seconds; /**< wall time refining the coarser level into this one, s */
  ps_refinement_stats refinement; /**< how the level's start was built */
  /** Contact pairs whose offset is still lowered after the last solve (where contact kept a
   *  split from opening fully; the state is intersection-free but thinner there); 0 normally. */
  int32_t reduced_offsets;
  /** Faces whose strain limit is still raised after the last solve; 0 normally. */
  int32_t raised_limits;
  /** Obstacle vertices the level's contact meets: fewer than the scene's on coarse levels
   *  when obstacles are progressive (PSQ §4.6); 0 without obstacles. */
  int32_t obstacle_vertices;
  /** How the progressive obstacles were refined into this level (PSQ §4.6; zeros without). */
  ps_refinement_stats obstacle_refinement;
  /** CG iterations refining projected Newton steps (ps_sim_def::solver_max_cg_iterations > 0;
   *  never in the coarse levels' proxy solves); 0 when refinement is off. */
  int32_t cg_iterations;
  /** Newton steps the line search lengthened beyond a whole step
   *  (ps_sim_def::solver_line_search_extrapolation = 1); 0 when it is off. */
  int32_t extrapolated_steps;
  /** How the level's refined start was brought under its strain limits (PSQ §4.4.5). */
  ps_strain_correction_stats strain_correction;
} ps_level_stats;

/** Statistics of `level` into *out. Levels not visited yet report zeros (NaN errors).
 *  Errors: PS_ERROR_OUT_OF_RANGE; PS_ERROR_INVALID_ARGUMENT for a progressive animation (see
 *  ps_sim_get_dynamic_level_stats()). */
PS_API int32_t ps_sim_get_level_stats(const ps_sim* sim, int32_t level, ps_level_stats* out);

/* ------------------------------------------------------- progressive animation --------- */
/*
 * A progressive animation (PS_SIM_PROGRESSIVE_DYNAMICS; Progressive Dynamics, Zhang, James and
 * Kaufman 2024, with PD++'s continuity): ps_sim_step_preview() animates level 0 frame by
 * frame; ps_sim_refine() then animates level 1, 2, ... over the same span, each from the
 * coarser level's frames. Frame 0 of a level is its initial state, frame k its state after
 * step k (time k·h); every computed level has as many frames as the preview. Frames are kept
 * on disk (temporary files), so memory does not grow with the number of steps. The calls below
 * give PS_ERROR_INVALID_ARGUMENT, naming the kind, on the other kinds of simulation.
 */

/** Number of frames of a computed level (previewed steps + 1) into *out.
 *  Errors: PS_ERROR_OUT_OF_RANGE (a level that does not exist or has not been computed). */
PS_API int32_t ps_sim_num_frames(const ps_sim* sim, int32_t level, int32_t* out);

/**
 * Positions of frame `frame` (0 to ps_sim_num_frames() − 1) of a computed level, (n × 3)
 * doubles, m, into out[capacity]; *count = 3n with n the level's vertex count. out is nullable
 * (size query). Errors: PS_ERROR_OUT_OF_RANGE (a level or frame not computed),
 * PS_ERROR_BUFFER_TOO_SMALL, PS_ERROR_IO (the frame file cannot be read).
 */
PS_API int32_t ps_sim_get_frame_positions(const ps_sim* sim, int32_t level, int32_t frame,
                                          double* out, size_t capacity, size_t* count);

/** Velocities of a frame, (n × 3) doubles, m/s; as ps_sim_get_frame_positions(). */
PS_API int32_t ps_sim_get_frame_velocities(const ps_sim* sim, int32_t level, int32_t frame,
                                           double* out, size_t capacity, size_t* count);

/**
 * Sets the preview's initial velocities, (n_0 × 3) doubles, m/s (count = 3 n_0, n_0 level 0's
 * vertex count; copied), before its first step; frame 0 of level 0 changes with them and finer
 * levels start from their prolongation. Errors (nothing changed): PS_ERROR_INVALID_ARGUMENT (a
 * wrong count or a NaN/Inf entry), PS_ERROR_WRONG_CALL_ORDER (after a preview step: restart
 * first), PS_ERROR_NULL_ARGUMENT.
 */
PS_API int32_t ps_sim_set_preview_velocities(ps_sim* sim, const double* velocities, size_t count);

/** Discards every level's frames and starts the preview again at rest from the current
 *  parameters (after ps_sim_set_param() and the like, to preview a variation). Initial
 *  velocities set before are discarded too. */
PS_API int32_t ps_sim_restart(ps_sim* sim);

/** One step of one level of a progressive animation: what produced frame `step`. */
typedef struct ps_step_stats {
  int32_t step;              /**< 1-based: the step from frame step − 1 to frame step */
  int32_t newton_iterations; /**< this step's Newton iterations */
  int32_t converged;         /**< 1 if the step's Newton solve met the tolerance */
  double time;               /**< simulated time after the step, s */
  double seconds;            /**< wall time of the step, s */
  double kinetic_energy;     /**< ½ vᵀ M v after the step, J (the level's masses) */
  double center_of_mass[3];  /**< Σ m x / Σ m after the step, m */
  /** how far the centre of mass has moved away from the preview's since frame 0, m:
   *  ‖(CoM − CoM⁰) − (CoM_preview − CoM_preview⁰)‖ (PD Fig. 19); 0 on level 0 */
  double com_deviation;
  /** VPD App. C eq. 18: continuity_error over the step's own solve residual, dimensionless
   *  (≤ 1 for implicit Euler on the level alone, larger where the prediction jumps) */
  double continuity;
  /** VPD App. C eq. 17: ‖xᵗ − x̃ᵗ‖_M, m (mass-weighted RMS), x̃ᵗ the midpoint estimate of the
   *  step's start from its neighbours */
  double continuity_error;
  /** VPD App. C eq. 19: mass-weighted RMS distance of the level, projected onto the coarser
   *  level, to the coarser frame, m; 0 on level 0 */
  double consistency;
} ps_step_stats;

/** Per-step statistics of a computed level, one ps_step_stats per step in order (steps 1 to
 *  ps_sim_num_frames() − 1), into out[capacity]; *count = the number of steps. out is nullable
 *  (size query). Errors: PS_ERROR_OUT_OF_RANGE, PS_ERROR_BUFFER_TOO_SMALL. */
PS_API int32_t ps_sim_get_step_stats(const ps_sim* sim, int32_t level, ps_step_stats* out,
                                     size_t capacity, size_t* count);

/** One level of a progressive animation: its size and work. */
typedef struct ps_dynamic_level_stats {
  int32_t level;             /**< which level */
  int32_t vertices;          /**< of the level's mesh */
  int32_t steps;             /**< steps animated at this level */
  int32_t newton_iterations; /**< over its steps */
  int32_t converged_steps;   /**< steps whose Newton solve met the tolerance */
  int32_t first_step;        /**< its frame 0 is the animation's frame first_step (a window) */
  double seconds;            /**< wall time of its steps, s */
} ps_dynamic_level_stats;

/** Statistics of a computed level into *out. Errors: PS_ERROR_OUT_OF_RANGE (a level that does
 *  not exist or has not been computed), PS_ERROR_NULL_ARGUMENT. */
PS_API int32_t ps_sim_get_dynamic_level_stats(const ps_sim* sim, int32_t level,
                                              ps_dynamic_level_stats* out);

/* ------------------------------------------------------- accuracy vs time -------------- */

/** What accuracy costs in time on one scene: progressive and direct results per level. */
typedef struct ps_accuracy ps_accuracy;

/** How a row's result was computed. */
typedef enum ps_method {
  PS_METHOD_PROGRESSIVE = 0, /**< preview, refinement level by level (PSQ) */
  PS_METHOD_DIRECT = 1,      /**< the level solved on its own with the same solver */
  PS_METHOD_FORCE32 = 0x7fffffff
} ps_method;

/** What ps_accuracy_def::direct_time_ratio multiplies. */
typedef enum ps_time_base {
  /** the progressive time to the converged finest level (the default) */
  PS_TIME_BASE_PIPELINE = 0,
  /** the coarse preview's time: a run capped at R stops as soon as it shows the preview at
   *  least R times faster than the direct solve */
  PS_TIME_BASE_PREVIEW = 1,
  PS_TIME_BASE_FORCE32 = 0x7fffffff
} ps_time_base;

/** One level's result, as `progsim accuracy` writes it to accuracy.csv. */
typedef struct ps_accuracy_row {
  ps_method method;
  int32_t level;             /**< 0 = coarsest */
  int32_t vertices;          /**< of the level's mesh */
  int32_t newton_iterations; /**< on the level */
  /** s: progressive, from the start until this level's equilibrium (coarser levels and
   *  refinements included); direct, the level's own solve over the load script. */
  double seconds;
  double refine_seconds; /**< s, building the level's start from the coarser level */
  /** Distance of the level's state, prolonged to the finest mesh, to the converged finest
   *  progressive result over the finest bounding-box diagonal: RMS and max over vertices. */
  double error_rms;
  double error_max;
  int32_t intersecting_pairs; /**< face pairs crossing in the final state (CGAL exact check) */
  /** 1 if the level ended at equilibrium (as ps_level_stats::equilibrium), progressive or direct.
   */
  int32_t converged;
  /** Load steps of the scene's script solved: all of them, except in a direct solve stopped by
   *  ps_accuracy_def::direct_time_ratio. */
  int32_t load_steps;
  /** 0 for a direct solve stopped by ps_accuracy_def::direct_time_ratio: its `seconds` is then
   *  only a lower bound of what the whole solve takes, and speed-ups against it are lower
   *  bounds too. 1 otherwise. */
  int32_t finished;
} ps_accuracy_row;

/** Which levels an accuracy run solves directly, for how long, and its progress reporting.
 *  Fill with ps_accuracy_def_init(), then change fields. */
typedef struct ps_accuracy_def {
  /** Levels solved directly, in this order (each in 0 to the finest). Nullable: NULL with
   *  num_direct_levels = 0 (the default) solves every level, coarsest first. Borrowed during
   *  the run call only. */
  const int32_t* direct_levels;
  int32_t num_direct_levels; /**< entries in direct_levels (0 to 64); default 0 */
  /** A direct solve stops within the Newton iteration that takes it past this many times the
   *  progressive time to the converged finest level (or the preview's, see direct_time_base);
   *  its row then has finished = 0 (a load step stopped inside is not counted in load_steps).
   *  On large scenes the direct finest solve can take hours; a limit still measures a lower
   *  bound of the speed-up. 0 (the default): no limit; negative or NaN:
   *  PS_ERROR_INVALID_ARGUMENT. */
  double direct_time_ratio;
  /** What direct_time_ratio multiplies; default PS_TIME_BASE_PIPELINE. Another value:
   *  PS_ERROR_INVALID_ARGUMENT. */
  ps_time_base direct_time_base;
  /** Nullable (default): called with done/100 and a phase such as "progressive level 1" or
   *  "direct level 0, load step 3 of 20": when a phase begins and after each load step of the
   *  preview and the direct solves (see ps_progress_fn). */
  ps_progress_fn progress;
  void* progress_user_data; /**< passed back to progress unchanged; default NULL */
  int32_t internal_cookie;  /**< set by ps_accuracy_def_init(); do not touch */
} ps_accuracy_def;

/** Fills def with defaults (every level solved directly, no time limit, no progress). def must
 *  not be NULL. */
PS_API void ps_accuracy_def_init(ps_accuracy_def* def);

/**
 * Runs the scene file (which needs a "progressive" section with coarse levels) progressively
 * and directly on the levels def names (every level by default), as `progsim accuracy` does.
 * Long: minutes to hours on large meshes; see ps_accuracy_def::progress and
 * ps_accuracy_def::direct_time_ratio.
 * @param def Nullable (defaults). Borrowed during the call.
 * @param out receives the results; caller owns, destroy with ps_accuracy_destroy().
 * Errors (message in ps_last_error()): PS_ERROR_IO, PS_ERROR_INVALID_SCENE (no coarse levels
 * among others), PS_ERROR_UNSUPPORTED (a dynamic scene), PS_ERROR_INVALID_ARGUMENT (a direct
 * level that does not exist, a negative time ratio), PS_ERROR_UNINITIALIZED_DEF,
 * PS_ERROR_INTERSECTING, PS_ERROR_CANCELLED, PS_ERROR_NULL_ARGUMENT.
 */
PS_API int32_t ps_accuracy_run_scene_file(const char* path, const ps_accuracy_def* def,
                                          ps_accuracy** out);

/** Destroys the results. Nullable (no-op). */
PS_API void ps_accuracy_destroy(ps_accuracy* accuracy);

/** The time limit the direct solves had, in seconds, into *out: direct_time_ratio times its
 *  base's time in this run; 0 without a limit. Errors: PS_ERROR_NULL_ARGUMENT. */
PS_API int32_t ps_accuracy_direct_time_limit(const ps_accuracy* accuracy, double* out);

/** Number of rows into *out: progressive levels first (coarsest first), then direct ones. */
PS_API int32_t ps_accuracy_num_rows(const ps_accuracy* accuracy, int32_t* out);

/** Row `index` into *out. Errors: PS_ERROR_OUT_OF_RANGE, PS_ERROR_NULL_ARGUMENT. */
PS_API int32_t ps_accuracy_get_row(const ps_accuracy* accuracy, int32_t index,
                                   ps_accuracy_row* out);

/** Writes accuracy.csv, accuracy.md and the three PNG plots (error_vs_time, error_by_level,
 *  time_by_level) into directory `dir` (created).
 *  Errors: PS_ERROR_IO naming the file, PS_ERROR_NULL_ARGUMENT. */
PS_API int32_t ps_accuracy_write(const ps_accuracy* accuracy, const char* dir);

#ifdef __cplusplus
}
#endif

#endif /* PROGSIM_H */
