// The translation unit that cmake/BuildSpeed.cmake compiles the shared precompiled headers with.
