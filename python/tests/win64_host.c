/* A minimal FMI 2.0 Co-Simulation host for the win64 library of an extracted FMU, compiled with
 * mingw-w64 and run under wine by python/tests/test_fmu_win64.py (which compares what it prints
 * with the linux64 library run through fmpy).
 *
 *   win64_host.exe UNZIPDIR MODEL GUID VR_OUT VR_BAD H K0 N [STATE_IN|- [STATE_OUT]]
 *
 * Loads UNZIPDIR/binaries/win64/MODEL.dll, instantiates it with UNZIPDIR/resources/, and
 *   - initializes at t = 0, sets the state STATE_IN when given (serialized by any platform's
 *     library, at t = K0*H), and steps N steps of H from t = K0*H;
 * printing `step K BITS` (K, the Real VR_OUT as the 16 hex digits of its IEEE-754 bits) after
 * each step. Then it checks, printing one line each:
 *   `states identical`   the state got after step N/2, set back, gives the same steps again;
 *   `bad value refused S` in a second instance, fmi2SetReal of NaN to the Real parameter
 *                         VR_BAD before initialization returns status S (0 would be accepted);
 * and serializes the state at the end into STATE_OUT when given. Any failed call: a line
 * `FAILED ...` on stderr and exit status 1.
 */
#include <windows.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <stdarg.h>

typedef void *Component;
typedef void *State;
typedef unsigned int VR;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*allocate)(size_t, size_t);
    void (*free)(void *);
    void *step_finished;
    void *environment;
} Callbacks;

typedef Component (*Instantiate)(const char *, int, const char *, const char *, const Callbacks *,
                                 int, int);
typedef int (*Setup)(Component, int, double, double, int, double);
typedef int (*NoArgs)(Component);
typedef void (*Free)(Component);
typedef int (*GetReal)(Component, const VR *, size_t, double *);
typedef int (*SetReal)(Component, const VR *, size_t, const double *);
typedef int (*DoStep)(Component, double, double, int);
typedef int (*GetState)(Component, State *);
typedef int (*SetState)(Component, State);
typedef int (*FreeState)(Component, State *);
typedef int (*StateSize)(Component, State, size_t *);
typedef int (*Serialize)(Component, State, char *, size_t);
typedef int (*Deserialize)(Component, const char *, size_t, State *);

static HMODULE lib;

static void *symbol(const char *name) {
    void *f = (void *)GetProcAddress(lib, name);
    if (!f) {
        fprintf(stderr, "FAILED: the library does not export %s\n", name);
        exit(1);
    }
    return f;
}

static void check(int status, const char *what) {
    if (status != 0) {
        fprintf(stderr, "FAILED: %s returned status %d\n", what, status);
        exit(1);
    }
}

static void logger(void *env, const char *instance, int status, const char *category,
                   const char *message, ...) {
    (void)env;
    va_list args;
    va_start(args, message);
    fprintf(stderr, "[%s %d %s] ", instance, status, category);
    vfprintf(stderr, message, args);
    fprintf(stderr, "\n");
    va_end(args);
}

static uint64_t bits(double x) {
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

/* Steps n steps of h from step index k0, printing (or, when `out` is given, storing) VR_OUT. */
static void run(Component c, DoStep step, GetReal get, VR vr, double h, long k0, long n,
                uint64_t *out) {
    for (long k = k0; k < k0 + n; k++) {
        check(step(c, k * h, h, 1), "fmi2DoStep");
        double y;
        check(get(c, &vr, 1, &y), "fmi2GetReal");
        if (out)
            out[k - k0] = bits(y);
        else
            printf("step %ld %016llx\n", k + 1, (unsigned long long)bits(y));
    }
}

static char *read_file(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "FAILED: cannot open %s\n", path);
        exit(1);
    }
    fseek(f, 0, SEEK_END);
    *size = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    char *data = malloc(*size);
    if (fread(data, 1, *size, f) != *size) {
        fprintf(stderr, "FAILED: cannot read %s\n", path);
        exit(1);
    }
    fclose(f);
    return data;
}

int main(int argc, char **argv) {
    if (argc < 9) {
        fprintf(stderr, "usage: %s UNZIPDIR MODEL GUID VR_OUT VR_BAD H K0 N [STATE_IN [STATE_OUT]]\n",
                argv[0]);
        return 2;
    }
    const char *dir = argv[1], *model = argv[2], *guid = argv[3];
    VR vr_out = (VR)atol(argv[4]), vr_bad = (VR)atol(argv[5]);
    double h = atof(argv[6]);
    long k0 = atol(argv[7]), n = atol(argv[8]);
    const char *state_in = argc > 9 && strcmp(argv[9], "-") != 0 ? argv[9] : NULL;
    const char *state_out = argc > 10 ? argv[10] : NULL;

    char path[4096], uri[4096];
    snprintf(path, sizeof path, "%s\\binaries\\win64\\%s.dll", dir, model);
    lib = LoadLibraryA(path);
    if (!lib) {
        fprintf(stderr, "FAILED: LoadLibrary %s: error %lu\n", path, GetLastError());
        return 1;
    }
    /* file:///Z:/dir/resources with forward slashes (Windows paths may use either). */
    snprintf(uri, sizeof uri, "file:///%s/resources", dir);
    for (char *p = uri; *p; p++)
        if (*p == '\\')
            *p = '/';

    Instantiate instantiate = (Instantiate)symbol("fmi2Instantiate");
    Setup setup = (Setup)symbol("fmi2SetupExperiment");
    NoArgs enter = (NoArgs)symbol("fmi2EnterInitializationMode");
    NoArgs exit_init = (NoArgs)symbol("fmi2ExitInitializationMode");
    NoArgs terminate = (NoArgs)symbol("fmi2Terminate");
    Free free_instance = (Free)symbol("fmi2FreeInstance");
    GetReal get = (GetReal)symbol("fmi2GetReal");
    SetReal set = (SetReal)symbol("fmi2SetReal");
    DoStep step = (DoStep)symbol("fmi2DoStep");
    GetState get_state = (GetState)symbol("fmi2GetFMUstate");
    SetState set_state = (SetState)symbol("fmi2SetFMUstate");
    FreeState free_state = (FreeState)symbol("fmi2FreeFMUstate");
    StateSize state_size = (StateSize)symbol("fmi2SerializedFMUstateSize");
    Serialize serialize = (Serialize)symbol("fmi2SerializeFMUstate");
    Deserialize deserialize = (Deserialize)symbol("fmi2DeSerializeFMUstate");

    Callbacks callbacks = {logger, calloc, free, NULL, NULL};
    Component c = instantiate("win64", 1 /* fmi2CoSimulation */, guid, uri, &callbacks, 0, 0);
    if (!c) {
        fprintf(stderr, "FAILED: fmi2Instantiate returned NULL (resources %s)\n", uri);
        return 1;
    }
    check(setup(c, 0, 0.0, 0.0, 0, 0.0), "fmi2SetupExperiment");
    check(enter(c), "fmi2EnterInitializationMode");
    check(exit_init(c), "fmi2ExitInitializationMode");

    if (state_in) {
        size_t size;
        char *data = read_file(state_in, &size);
        State s = NULL;
        check(deserialize(c, data, size, &s), "fmi2DeSerializeFMUstate");
        check(set_state(c, s), "fmi2SetFMUstate");
        check(free_state(c, &s), "fmi2FreeFMUstate");
        free(data);
    }

    long half = n / 2;
    run(c, step, get, vr_out, h, k0, half, NULL);
    State middle = NULL;
    check(get_state(c, &middle), "fmi2GetFMUstate");
    run(c, step, get, vr_out, h, k0 + half, n - half, NULL);

    /* Back to the middle: the second half again, bit for bit. */
    uint64_t *first = malloc(sizeof(uint64_t) * (size_t)(n - half + 1));
    uint64_t *again = malloc(sizeof(uint64_t) * (size_t)(n - half + 1));
    State end = NULL;
    check(get_state(c, &end), "fmi2GetFMUstate");
    check(set_state(c, middle), "fmi2SetFMUstate");
    run(c, step, get, vr_out, h, k0 + half, n - half, again);
    check(set_state(c, middle), "fmi2SetFMUstate");
    run(c, step, get, vr_out, h, k0 + half, n - half, first);
    if (memcmp(first, again, sizeof(uint64_t) * (size_t)(n - half)) != 0) {
        fprintf(stderr, "FAILED: the second half differs after fmi2SetFMUstate\n");
        return 1;
    }
    printf("states identical\n");


    if (state_out) {
        check(set_state(c, end), "fmi2SetFMUstate");
        size_t size;
        check(state_size(c, end, &size), "fmi2SerializedFMUstateSize");
        char *data = malloc(size);
        check(serialize(c, end, data, size), "fmi2SerializeFMUstate");
        FILE *f = fopen(state_out, "wb");
        if (!f || fwrite(data, 1, size, f) != size) {
            fprintf(stderr, "FAILED: cannot write %s\n", state_out);
            return 1;
        }
        fclose(f);
        free(data);
    }
    check(free_state(c, &middle), "fmi2FreeFMUstate");
    check(free_state(c, &end), "fmi2FreeFMUstate");
    check(terminate(c), "fmi2Terminate");
    free_instance(c);
    free(first);
    free(again);

    Component bad = instantiate("bad", 1, guid, uri, &callbacks, 0, 0);
    if (!bad) {
        fprintf(stderr, "FAILED: the second fmi2Instantiate returned NULL\n");
        return 1;
    }
    check(setup(bad, 0, 0.0, 0.0, 0, 0.0), "fmi2SetupExperiment");
    double nan = NAN;
    printf("bad value refused %d\n", set(bad, &vr_bad, 1, &nan));
    free_instance(bad);
    return 0;
}
