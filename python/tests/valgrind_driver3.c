/*
 * A minimal FMI 3.0 Co-Simulation host for running an FMU's shared library under valgrind
 * (scripts/valgrind_fmu). No FMI headers needed: the few types are declared here.
 *
 *   valgrind_driver3 LIBRARY.so TOKEN RESOURCE_PATH SHAPE_VRS POINTS [STEPS] [STEP_SIZE]
 *
 * SHAPE_VRS: the value references of the shape_x and shape_y arrays ("a,b"), POINTS their
 * element count (scripts/valgrind_fmu reads both from modelDescription.xml).
 *
 * Cycle: instantiate, configuration mode, initialization with a stop time, STEPS fmi3DoSteps
 * reading both arrays and the scalars, get/set FMU state (roll back and compare), serialize /
 * deserialize, hostile input (a corrupt buffer, freed and garbage state handles, a wrong
 * element count, NULL out-arguments of fmi3DoStep, unsupported functions), terminate, reset,
 * and fmi3FreeInstance with FMU states the host never freed, dlclose.
 * Exit status 0 when every call answered as expected, 2 otherwise.
 */
#include <dlfcn.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef void *fmi3Instance;
typedef void *fmi3FMUState;
typedef uint32_t fmi3ValueReference;
typedef enum { fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal } fmi3Status;
typedef void (*fmi3LogMessageCallback)(void *, fmi3Status, const char *, const char *);

enum { VR_E_KIN = 32, VR_E_STRAIN = 33, VR_NEWTON = 34 };

static int failures = 0;
static int messages = 0;

static void logger(void *env, fmi3Status status, const char *category, const char *message) {
    (void)env;
    (void)status;
    messages += category != NULL && strlen(message) > 0;
}

static void *sym(void *lib, const char *name) {
    void *f = dlsym(lib, name);
    if (!f) {
        fprintf(stderr, "missing symbol %s\n", name);
        exit(2);
    }
    return f;
}

static void expect(fmi3Status got, fmi3Status want, const char *what) {
    if (got != want) {
        fprintf(stderr, "%s: status %d, expected %d\n", what, got, want);
        failures++;
    }
}

#define FN(name, ret, ...) ret (*name)(__VA_ARGS__) = sym(lib, #name)

int main(int argc, char **argv) {
    if (argc < 6) {
        fprintf(stderr, "usage: %s LIB TOKEN RESOURCE_PATH SHAPE_VRS POINTS [STEPS] [STEP_SIZE]\n", argv[0]);
        return 2;
    }
    fmi3ValueReference shape[2];
    if (sscanf(argv[4], "%u,%u", &shape[0], &shape[1]) != 2) return 2;
    size_t points = (size_t)atoi(argv[5]);
    int steps = argc > 6 ? atoi(argv[6]) : 100;
    double h = argc > 7 ? atof(argv[7]) : 1e-5;
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 2;
    }
    FN(fmi3InstantiateCoSimulation, fmi3Instance, const char *, const char *, const char *, bool, bool,
       bool, bool, const fmi3ValueReference *, size_t, void *, fmi3LogMessageCallback, void *);
    FN(fmi3FreeInstance, void, fmi3Instance);
    FN(fmi3EnterConfigurationMode, fmi3Status, fmi3Instance);
    FN(fmi3ExitConfigurationMode, fmi3Status, fmi3Instance);
    FN(fmi3EnterInitializationMode, fmi3Status, fmi3Instance, bool, double, double, bool, double);
    FN(fmi3ExitInitializationMode, fmi3Status, fmi3Instance);
    FN(fmi3DoStep, fmi3Status, fmi3Instance, double, double, bool, bool *, bool *, bool *, double *);
    FN(fmi3GetFloat64, fmi3Status, fmi3Instance, const fmi3ValueReference *, size_t, double *, size_t);
    FN(fmi3GetInt32, fmi3Status, fmi3Instance, const fmi3ValueReference *, size_t, int32_t *, size_t);
    FN(fmi3GetFMUState, fmi3Status, fmi3Instance, fmi3FMUState *);
    FN(fmi3SetFMUState, fmi3Status, fmi3Instance, fmi3FMUState);
    FN(fmi3FreeFMUState, fmi3Status, fmi3Instance, fmi3FMUState *);
    FN(fmi3SerializedFMUStateSize, fmi3Status, fmi3Instance, fmi3FMUState, size_t *);
    FN(fmi3SerializeFMUState, fmi3Status, fmi3Instance, fmi3FMUState, uint8_t *, size_t);
    FN(fmi3DeserializeFMUState, fmi3Status, fmi3Instance, const uint8_t *, size_t, fmi3FMUState *);
    FN(fmi3EnterEventMode, fmi3Status, fmi3Instance);
    FN(fmi3Terminate, fmi3Status, fmi3Instance);
    FN(fmi3Reset, fmi3Status, fmi3Instance);

    fmi3Instance c = fmi3InstantiateCoSimulation("valgrind", argv[2], argv[3], false, true, false,
                                                 false, NULL, 0, NULL, logger, NULL);
    if (!c) {
        fprintf(stderr, "fmi3InstantiateCoSimulation failed\n");
        return 2;
    }
    expect(fmi3EnterConfigurationMode(c), fmi3OK, "fmi3EnterConfigurationMode");
    expect(fmi3ExitConfigurationMode(c), fmi3OK, "fmi3ExitConfigurationMode");
    expect(fmi3EnterInitializationMode(c, false, 0, 0.0, true, 10.0), fmi3OK, "fmi3EnterInitializationMode");
    expect(fmi3ExitInitializationMode(c), fmi3OK, "fmi3ExitInitializationMode");

    double *values = calloc(2 * points + 2, sizeof(double));
    const fmi3ValueReference scalars[2] = {VR_E_KIN, VR_E_STRAIN};
    double t = 0.0, last = 0.0;
    bool event, terminate, early;
    fmi3FMUState mid = NULL;
    double at_mid = 0.0;
    for (int k = 0; k < steps; k++) {
        expect(fmi3DoStep(c, t, h, false, &event, &terminate, &early, &last), fmi3OK, "fmi3DoStep");
        t = last;
        expect(fmi3GetFloat64(c, shape, 2, values, 2 * points), fmi3OK, "fmi3GetFloat64 (arrays)");
        expect(fmi3GetFloat64(c, scalars, 2, values + 2 * points, 2), fmi3OK, "fmi3GetFloat64");
        int32_t newton;
        const fmi3ValueReference vr_newton = VR_NEWTON;
        expect(fmi3GetInt32(c, &vr_newton, 1, &newton, 1), fmi3OK, "fmi3GetInt32");
        if (k == steps / 2) {
            expect(fmi3GetFMUState(c, &mid), fmi3OK, "fmi3GetFMUState");
            at_mid = t;
        }
    }
    double end_value = values[points - 1];
    /* roll back to the middle and step to the end again: the same shape */
    expect(fmi3SetFMUState(c, mid), fmi3OK, "fmi3SetFMUState");
    t = at_mid;
    for (int k = steps / 2 + 1; k < steps; k++) {
        expect(fmi3DoStep(c, t, h, false, &event, &terminate, &early, &last), fmi3OK, "fmi3DoStep (again)");
        t = last;
    }
    expect(fmi3GetFloat64(c, shape, 2, values, 2 * points), fmi3OK, "fmi3GetFloat64 (again)");
    if (steps > 1 && values[points - 1] != end_value) {
        fprintf(stderr, "the rolled-back run differs\n");
        failures++;
    }
    size_t size = 0;
    expect(fmi3SerializedFMUStateSize(c, mid, &size), fmi3OK, "fmi3SerializedFMUStateSize");
    uint8_t *bytes = malloc(size);
    expect(fmi3SerializeFMUState(c, mid, bytes, size), fmi3OK, "fmi3SerializeFMUState");
    fmi3FMUState copy = NULL;
    expect(fmi3DeserializeFMUState(c, bytes, size, &copy), fmi3OK, "fmi3DeserializeFMUState");
    bytes[size / 2] ^= 0x55;
    fmi3FMUState bad = NULL;
    expect(fmi3DeserializeFMUState(c, bytes, size, &bad), fmi3Error, "corrupt bytes");
    expect(fmi3SetFMUState(c, copy), fmi3OK, "fmi3SetFMUState (deserialized)");
    fmi3FMUState freed = copy;
    expect(fmi3FreeFMUState(c, &copy), fmi3OK, "fmi3FreeFMUState");
    expect(fmi3SetFMUState(c, freed), fmi3Error, "a freed state");
    expect(fmi3SetFMUState(c, (fmi3FMUState)values), fmi3Error, "a garbage state");
    expect(fmi3GetFloat64(c, shape, 1, values, points + 1), fmi3Error, "a wrong element count");
    expect(fmi3DoStep(c, t, h, false, NULL, &terminate, &early, &last), fmi3Error, "NULL eventHandlingNeeded");
    expect(fmi3EnterEventMode(c), fmi3Error, "fmi3EnterEventMode");
    expect(fmi3Terminate(c), fmi3OK, "fmi3Terminate");
    expect(fmi3Reset(c), fmi3OK, "fmi3Reset");
    fmi3FMUState unfreed = NULL;
    expect(fmi3GetFMUState(c, &unfreed), fmi3OK, "fmi3GetFMUState (left to the instance)");
    fmi3FreeInstance(c); /* frees `mid` and `unfreed` */
    free(bytes);
    free(values);
    dlclose(lib);
    if (messages == 0) {
        fprintf(stderr, "the logger was never called\n");
        failures++;
    }
    printf("%d steps, %zu points, %d messages, %d failures\n", steps, points, messages, failures);
    return failures ? 2 : 0;
}
