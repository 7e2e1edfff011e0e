/*
 * A minimal FMI 2.0 Co-Simulation host for running an FMU's shared library under valgrind
 * (scripts/valgrind_fmu). No FMI headers needed: the few types are declared here.
 *
 *   valgrind_driver LIBRARY.so GUID RESOURCE_URI [STEPS] [STEP_SIZE] [FORCING] [INPUT] [OUTPUTS]
 *
 * FORCING: the value references of F,Omega (set to 0.9, 3500 before initialization), "-" for a
 * scene without a harmonic load; INPUT: the value reference of the input driven over the steps
 * (1e-3 * (k % 3)), "-" for none; OUTPUTS: two output value references read with E_kin and
 * E_strain. Defaults: the paper scenes' "9,10", "1000" (f_ctrl) and "2000,2001" (w_mid, v_mid);
 * scripts/valgrind_fmu reads them from each FMU's modelDescription.xml.
 *
 * Cycle: instantiate, setupExperiment, set parameters, enter/exit initialization, STEPS doSteps
 * reading every output, get/set FMU state (roll back and compare), serialize / deserialize,
 * hostile state handling (a corrupt buffer, garbage in deserialize's output slot, stale, double
 * freed, foreign, garbage and unmapped handles: each refused without touching its memory),
 * a few refused calls (error paths with the logger), terminate, and freeInstance with FMU
 * states the host never freed (they must go with the instance: no definite leak), dlclose.
 * Exit status 0 when every call answered as expected, 2 otherwise.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Byte;
typedef const char *fmi2String;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum { fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated } fmi2StatusKind;

typedef struct {
    void (*logger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(fmi2ComponentEnvironment, fmi2Status);
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

/* value references every scene has (src/scene/variables.rs) */
enum { VR_E_KIN = 32, VR_E_STRAIN = 33, VR_NEWTON = 34 };

/* "a,b" into two value references; "-" (none) gives 0; 1 when parsed */
static int parse_pair(const char *text, fmi2ValueReference *a, fmi2ValueReference *b) {
    if (strcmp(text, "-") == 0) return 0;
    if (sscanf(text, "%u,%u", a, b) != 2) {
        fprintf(stderr, "expected two value references \"a,b\" or \"-\", got \"%s\"\n", text);
        exit(2);
    }
    return 1;
}

static int messages = 0;

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    (void)env;
    char buffer[2048];
    va_list args;
    va_start(args, message);
    vsnprintf(buffer, sizeof buffer, message ? message : "(null)", args);
    va_end(args);
    messages++;
    fprintf(stderr, "  [log %s status=%d %s] %s\n", instance ? instance : "?", (int)status, category ? category : "",
            buffer);
}

static int failures = 0;

#define EXPECT(call, want)                                                                                    \
    do {                                                                                                      \
        fmi2Status s_ = (call);                                                                               \
        if (s_ != (want)) {                                                                                   \
            fprintf(stderr, "FAIL %s:%d: %s returned %d, expected %d\n", __FILE__, __LINE__, #call, (int)s_, \
                    (int)(want));                                                                             \
            failures++;                                                                                       \
        }                                                                                                     \
    } while (0)

#define LOAD(name)                                                                                            \
    name##_t name = (name##_t)dlsym(lib, #name);                                                              \
    if (!name) {                                                                                              \
        fprintf(stderr, "missing symbol %s\n", #name);                                                        \
        return 2;                                                                                             \
    }

typedef fmi2Component (*fmi2Instantiate_t)(fmi2String, fmi2Type, fmi2String, fmi2String,
                                            const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
typedef void (*fmi2FreeInstance_t)(fmi2Component);
typedef fmi2Status (*fmi2SetupExperiment_t)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
typedef fmi2Status (*fmi2EnterInitializationMode_t)(fmi2Component);
typedef fmi2Status (*fmi2ExitInitializationMode_t)(fmi2Component);
typedef fmi2Status (*fmi2Terminate_t)(fmi2Component);
typedef fmi2Status (*fmi2GetReal_t)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*fmi2SetReal_t)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Real *);
typedef fmi2Status (*fmi2GetInteger_t)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Integer *);
typedef fmi2Status (*fmi2DoStep_t)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef fmi2Status (*fmi2GetFMUstate_t)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*fmi2SetFMUstate_t)(fmi2Component, fmi2FMUstate);
typedef fmi2Status (*fmi2FreeFMUstate_t)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*fmi2SerializedFMUstateSize_t)(fmi2Component, fmi2FMUstate, size_t *);
typedef fmi2Status (*fmi2SerializeFMUstate_t)(fmi2Component, fmi2FMUstate, fmi2Byte *, size_t);
typedef fmi2Status (*fmi2DeSerializeFMUstate_t)(fmi2Component, const fmi2Byte *, size_t, fmi2FMUstate *);
typedef fmi2Status (*fmi2GetRealStatus_t)(fmi2Component, fmi2StatusKind, fmi2Real *);

int main(int argc, char **argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: %s LIBRARY.so GUID RESOURCE_URI [STEPS] [STEP_SIZE] [FORCING] [INPUT] [OUTPUTS]\n",
                argv[0]);
        return 2;
    }
    const char *path = argv[1], *guid = argv[2], *resources = argv[3];
    int steps = argc > 4 ? atoi(argv[4]) : 100;
    double h = argc > 5 ? atof(argv[5]) : 1e-5;
    fmi2ValueReference vr_forcing[2] = {9, 10}, vr_ctrl = 1000, vr_out[4] = {2000, 2001, VR_E_KIN, VR_E_STRAIN};
    int forced = argc > 6 ? parse_pair(argv[6], &vr_forcing[0], &vr_forcing[1]) : 1;
    int driven = 1;
    if (argc > 7 && strcmp(argv[7], "-") == 0) driven = 0;
    else if (argc > 7 && sscanf(argv[7], "%u", &vr_ctrl) != 1) {
        fprintf(stderr, "expected an input value reference or \"-\", got \"%s\"\n", argv[7]);
        return 2;
    }
    if (argc > 8 && !parse_pair(argv[8], &vr_out[0], &vr_out[1])) {
        fprintf(stderr, "OUTPUTS: two output value references are needed\n");
        return 2;
    }

    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 2;
    }
    LOAD(fmi2Instantiate)
    LOAD(fmi2FreeInstance)
    LOAD(fmi2SetupExperiment)
    LOAD(fmi2EnterInitializationMode)
    LOAD(fmi2ExitInitializationMode)
    LOAD(fmi2Terminate)
    LOAD(fmi2GetReal)
    LOAD(fmi2SetReal)
    LOAD(fmi2GetInteger)
    LOAD(fmi2DoStep)
    LOAD(fmi2GetFMUstate)
    LOAD(fmi2SetFMUstate)
    LOAD(fmi2FreeFMUstate)
    LOAD(fmi2SerializedFMUstateSize)
    LOAD(fmi2SerializeFMUstate)
    LOAD(fmi2DeSerializeFMUstate)
    LOAD(fmi2GetRealStatus)

    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    fmi2Component c = fmi2Instantiate("valgrind", fmi2CoSimulation, guid, resources, &cb, 0, 1);
    if (!c) {
        fprintf(stderr, "fmi2Instantiate returned NULL\n");
        return 2;
    }
    /* a refused call before initialization (error path + logger) */
    EXPECT(fmi2DoStep(c, 0.0, h, 1), fmi2Error);
    EXPECT(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), fmi2OK);
    const fmi2Real forcing[2] = {0.9, 3500.0};
    if (forced) EXPECT(fmi2SetReal(c, vr_forcing, 2, forcing), fmi2OK);
    EXPECT(fmi2EnterInitializationMode(c), fmi2OK);
    EXPECT(fmi2ExitInitializationMode(c), fmi2OK);

    const fmi2ValueReference vr_newton = VR_NEWTON, vr_bad = 12345;
    fmi2Real out[4], first[4], again[4], t_last = -1.0;
    fmi2Integer newton = 0;
    fmi2FMUstate state = NULL, restored = NULL;
    int half = steps / 2;
    for (int k = 0; k < steps; k++) {
        if (k == half) EXPECT(fmi2GetFMUstate(c, &state), fmi2OK);
        fmi2Real ctrl = 1e-3 * (k % 3);
        if (driven) EXPECT(fmi2SetReal(c, &vr_ctrl, 1, &ctrl), fmi2OK);
        EXPECT(fmi2DoStep(c, k * h, h, 1), fmi2OK);
        EXPECT(fmi2GetReal(c, vr_out, 4, out), fmi2OK);
        EXPECT(fmi2GetInteger(c, &vr_newton, 1, &newton), fmi2OK);
        if (!isfinite(out[0])) {
            fprintf(stderr, "FAIL: output %u not finite at step %d\n", vr_out[0], k);
            failures++;
        }
    }
    memcpy(first, out, sizeof out);

    /* roll back, re-step: identical */
    EXPECT(fmi2SetFMUstate(c, state), fmi2OK);
    for (int k = half; k < steps; k++) {
        fmi2Real ctrl = 1e-3 * (k % 3);
        if (driven) EXPECT(fmi2SetReal(c, &vr_ctrl, 1, &ctrl), fmi2OK);
        EXPECT(fmi2DoStep(c, k * h, h, 1), fmi2OK);
    }
    EXPECT(fmi2GetReal(c, vr_out, 4, again), fmi2OK);
    if (memcmp(first, again, sizeof first) != 0) {
        fprintf(stderr, "FAIL: re-stepping after fmi2SetFMUstate differs\n");
        failures++;
    }

    /* serialize, deserialize, set */
    size_t size = 0;
    EXPECT(fmi2SerializedFMUstateSize(c, state, &size), fmi2OK);
    fmi2Byte *bytes = malloc(size ? size : 1);
    EXPECT(fmi2SerializeFMUstate(c, state, bytes, size), fmi2OK);
    EXPECT(fmi2DeSerializeFMUstate(c, bytes, size, &restored), fmi2OK);
    EXPECT(fmi2SetFMUstate(c, restored), fmi2OK);
    /* *FMUstate is an output of deserialize: a held state there is not reused (it stays valid
       and owned by the instance), garbage there is not read; a corrupt buffer is refused */
    fmi2FMUstate held = restored, unmapped = (fmi2FMUstate)0x10;
    EXPECT(fmi2DeSerializeFMUstate(c, bytes, size, &restored), fmi2OK);
    EXPECT(fmi2SetFMUstate(c, held), fmi2OK);
    fmi2FMUstate slot = unmapped;
    EXPECT(fmi2DeSerializeFMUstate(c, bytes, size, &slot), fmi2OK);
    EXPECT(fmi2DeSerializeFMUstate(c, "garbage", 7, &restored), fmi2Error);
    bytes[size / 2] ^= 0x40;
    EXPECT(fmi2DeSerializeFMUstate(c, bytes, size, &slot), fmi2Error);
    free(bytes);
    EXPECT(fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t_last), fmi2OK);

    /* stale and double-freed handles: refused, nothing read, also after many more states came
       and went (handles are tokens that are never given out again) */
    fmi2FMUstate stale = state;
    EXPECT(fmi2FreeFMUstate(c, &state), fmi2OK);
    for (int k = 0; k < 100; k++) {
        fmi2FMUstate tmp = NULL;
        EXPECT(fmi2GetFMUstate(c, &tmp), fmi2OK);
        if (tmp == stale) failures++;
        EXPECT(fmi2FreeFMUstate(c, &tmp), fmi2OK);
    }
    EXPECT(fmi2SetFMUstate(c, stale), fmi2Error);
    EXPECT(fmi2SerializedFMUstateSize(c, stale, &size), fmi2Error);
    EXPECT(fmi2FreeFMUstate(c, &stale), fmi2Error);
    EXPECT(fmi2FreeFMUstate(c, &state), fmi2OK); /* NULL now: ignored */
    EXPECT(fmi2FreeFMUstate(c, &restored), fmi2OK);
    /* garbage handles: uninitialised heap (valgrind reports any read of it), unmapped */
    fmi2FMUstate junk = malloc(64);
    EXPECT(fmi2SetFMUstate(c, junk), fmi2Error);
    EXPECT(fmi2FreeFMUstate(c, &junk), fmi2Error);
    EXPECT(fmi2SetFMUstate(c, unmapped), fmi2Error);
    char out_buf[16];
    EXPECT(fmi2SerializeFMUstate(c, unmapped, out_buf, sizeof out_buf), fmi2Error);
    free(junk);
    /* garbage in fmi2GetFMUstate's slot: a new state (fmi2Warning), the garbage is not read */
    fmi2FMUstate fresh = unmapped;
    EXPECT(fmi2GetFMUstate(c, &fresh), fmi2Warning);
    /* another instance's state: refused here; that instance is freed with its state unfreed */
    fmi2Component e = fmi2Instantiate("valgrind3", fmi2CoSimulation, guid, resources, &cb, 0, 0);
    fmi2FMUstate foreign = NULL;
    if (e) {
        EXPECT(fmi2GetFMUstate(e, &foreign), fmi2OK);
        EXPECT(fmi2SetFMUstate(c, foreign), fmi2Error);
        EXPECT(fmi2FreeFMUstate(c, &foreign), fmi2Error);
        fmi2FreeInstance(e);
    } else {
        failures++;
    }
    /* left for fmi2FreeInstance: held, slot, fresh and one more */
    fmi2FMUstate unfreed = NULL;
    EXPECT(fmi2GetFMUstate(c, &unfreed), fmi2OK);

    /* refused calls: unknown value reference, NULL state, NaN input or forcing (the instance may be
       in the error state afterwards, so terminate's answer is not checked) */
    EXPECT(fmi2GetReal(c, &vr_bad, 1, out), fmi2Error);
    EXPECT(fmi2SetFMUstate(c, NULL), fmi2Error);
    fmi2Real nan_value = NAN;
    if (driven || forced) EXPECT(fmi2SetReal(c, driven ? &vr_ctrl : &vr_forcing[0], 1, &nan_value), fmi2Error);
    (void)fmi2Terminate(c);
    fmi2FreeInstance(c);

    /* a second instance that is freed without terminating nor initializing */
    fmi2Component d = fmi2Instantiate("valgrind2", fmi2CoSimulation, guid, resources, &cb, 0, 0);
    if (d) fmi2FreeInstance(d);
    else failures++;

    dlclose(lib);
    printf("%s: %d steps of %g s, output %u = %.17g, %d log messages, %d failures\n", path, steps, h, vr_out[0],
           first[0], messages, failures);
    return failures ? 2 : 0;
}
