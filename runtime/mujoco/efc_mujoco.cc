// Implemented by the MuJoCo backend work (efc_mujoco.h).
