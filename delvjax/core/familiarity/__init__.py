"""Route following by visual familiarity (docs/familiarity.md): rotational image differences, the
familiarity models (perfect memory, InfoMax, a mushroom body) and route experiments."""
