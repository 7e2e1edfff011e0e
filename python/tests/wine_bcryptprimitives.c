/* Test-only stand-in for Windows' bcryptprimitives.dll under wine 8, which lacks it: Rust's
 * standard library (in the win64 FMU library) imports ProcessPrng from it, as on Windows 10 and
 * later, where the system's DLL is always present. Placed beside the test host's executable by
 * python/tests/test_fmu_win64.py; it never goes into an FMU. */
#include <windows.h>

/* advapi32's RtlGenRandom, exported as SystemFunction036. */
BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length) {
    while (length > 0) {
        ULONG chunk = length > 0x10000000 ? 0x10000000 : (ULONG)length;
        if (!SystemFunction036(data, chunk))
            return FALSE;
        data += chunk;
        length -= chunk;
    }
    return TRUE;
}
